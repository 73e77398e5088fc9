// A shock in the porous Ryugu target in SPH (docs/physics.md section 2): a planar impact of two
// plates of the porous target material (basalt_matrix_ryugu without its strength, so that the flow is
// the hydrodynamic one of the reference) must reach the porous Hugoniot state computed independently
// from the P-alpha relations and the Rankine-Hugoniot conditions (tests/support/porous_hugoniot.hpp),
// within 5 % in pressure and particle velocity. The two plates are of the same material, so the contact
// moves at half the impact speed and both shocks carry the Hugoniot state at u_p = v/2 in the frame of
// the unshocked material. The solver's whole porous path runs: porous pressure, crush-curve return,
// consistent distention rate, KDK integration of the distention.
// tests/sph_core/test_porous_shock.cpp checks the same relations with an independent 1D Lagrangian
// scheme (the P-alpha rate form against the algebraic Hugoniot, no SPH); this test checks the solver.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "craterkit/sph/run/standard_problem_config.hpp"
#include "support/porous_hugoniot.hpp"

using namespace craterkit::sph;
namespace ts = craterkit::test_support;

namespace {

void check_porous_plates(double impact_velocity) {
  omp_set_num_threads(1);  // 5040 particles: two threads cost more in synchronisation than they gain
  StandardProblemConfig config;
  PlateImpactSetup setup;
  setup.projectile_material = "basalt_matrix_ryugu";
  setup.target_material = "basalt_matrix_ryugu";
  setup.impact_velocity = impact_velocity;
  setup.particle_spacing = 1e-3;
  setup.projectile_thickness = 70 * setup.particle_spacing;
  setup.target_thickness = 70 * setup.particle_spacing;
  config.problem = setup;
  // Constant Monaghan-Gingold viscosity (alpha = 1, beta = 2, docs/physics.md defaults). With the
  // Morris-Monaghan switch the viscosity decays behind the front and the stiff matrix rings (pressure
  // swinging between -50 and +230 MPa around 107 MPa at 400 m/s); every swing above P_s compacts fully
  // and irreversibly, so the plateau ends at alpha = 1, rho 3 % above the Hugoniot (docs/validation.md).
  config.simulation.solver.viscosity.viscosity_switch = ViscositySwitch::none;
  ProblemSetup problem = make_plate_impact(setup, config.simulation.solver.smoothing.eta,
                                           config.simulation.solver.viscosity.alpha);
  for (auto& material : problem.materials) material.strength.reset();  // the hydrodynamic reference
  const auto& target = problem.materials[1];
  const double u_p = 0.5 * impact_velocity;
  const auto reference =
      ts::porous_hugoniot_at_particle_velocity(target.eos, target.porosity->crush_curve, u_p);
  // Until the shocked target is 22 particle spacings long (two margins and ten spacings to average over).
  const double end_time = 22.0 * setup.particle_spacing / (reference.shock_velocity - u_p);
  Simulation sim(config.simulation.solver, std::move(problem));
  while (sim.time() < end_time) sim.step(end_time);
  // Shocked target: between the contact and the shock front, away from both by a few particle spacings
  // (shock width; the start-up transient at the contact, where the first particles are over-heated).
  const double contact = u_p * end_time;
  const double front = reference.shock_velocity * end_time;
  const double margin = 6.0 * setup.particle_spacing;
  double pressure = 0, velocity = 0, distention = 0, density = 0, peak = 0, count = 0;
  double peak_ahead = 0;  // the largest peak pressure of the target ahead of the front
  const auto& p = sim.particles();
  if (const char* out = std::getenv("CRATERKIT_VALIDATION_OUT")) {
    // One lattice column, for the validation figure (docs/scripts/plot_porosity.py).
    std::ofstream csv(std::string(out) + "/porous_shock_" +
                      std::to_string(static_cast<int>(impact_velocity)) + ".csv");
    csv << "# hugoniot pressure_Pa " << reference.pressure << " particle_velocity " << u_p << " distention "
        << reference.distention << " bulk_density " << reference.bulk_density << " shock_velocity "
        << reference.shock_velocity << " time " << end_time << " margin " << margin << "\n";
    csv << "material,x,pressure_Pa,distention,density,vx\n";
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.y[i] < setup.particle_spacing && p.z[i] < setup.particle_spacing) {
        csv << p.material[i] << ',' << p.x[i] << ',' << p.pressure[i] << ',' << p.distention[i] << ','
            << p.density[i] << ',' << p.vx[i] << '\n';
      }
    }
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.material[i] == 1 && p.x[i] > contact + margin && p.x[i] < front - margin) {
      pressure += p.pressure[i];
      velocity += p.vx[i];
      distention += p.distention[i];
      density += p.density[i];
      peak += p.peak_pressure[i];
      count += 1;
    }
    if (p.material[i] == 1 && p.x[i] > front + margin) peak_ahead = std::max(peak_ahead, p.peak_pressure[i]);
  }
  ASSERT_GT(count, 36 * 4);  // at least four lattice planes
  pressure /= count;
  velocity /= count;
  distention /= count;
  density /= count;
  peak /= count;
  std::printf(
      "porous plates %.0f m/s: Hugoniot P %.4g MPa u_p %.4g m/s alpha %.4f rho %.5g U_s %.4g | SPH P %.4g "
      "MPa "
      "u %.4g m/s alpha %.4f rho %.5g (%.0f particles)\n",
      impact_velocity, reference.pressure * 1e-6, u_p, reference.distention, reference.bulk_density,
      reference.shock_velocity, pressure * 1e-6, velocity, distention, density, count);
  EXPECT_NEAR(pressure / reference.pressure, 1.0, 0.05);
  EXPECT_NEAR(velocity / u_p, 1.0, 0.05);
  // Reported with the bound of the solver-free scheme of test_porous_shock (1 %), which the SPH plateau
  // need not meet; the requirement is on P and u_p.
  EXPECT_NEAR(density / reference.bulk_density, 1.0, 0.05);
  // The peak pressure each particle recorded (Particles::peak_pressure). Below full compaction (400 m/s) the
  // front is smooth and the peak is the Hugoniot pressure. At full compaction (1000 m/s) the stiff compacted
  // matrix rings behind the front, and every particle's peak lies well above the plateau it settles to: +72 %
  // with this viscosity, +39 % with alpha = 2, beta = 4, +133 % with alpha = 0.5, beta = 1, the same at
  // Courant 0.3, 0.15 and 0.075 (docs/validation.md, "Peak pressures"); there only the bound holds. Ahead of
  // the compaction front the particles have seen the elastic precursor, which P-alpha caps near the crush
  // onset P_e (1 MPa, 1 % of the 400 m/s Hugoniot pressure and 0.2 % of the 1000 m/s one).
  const double elastic_pressure = target.porosity->crush_curve.elastic_pressure;
  std::printf(
      "  peak pressure: shocked %.4g MPa (Hugoniot %.4g), largest ahead of the front %.3g MPa (P_e %.3g)\n",
      peak * 1e-6, reference.pressure * 1e-6, peak_ahead * 1e-6, elastic_pressure * 1e-6);
  if (reference.distention > 1.0) {
    EXPECT_NEAR(peak / reference.pressure, 1.0, 0.05);
  } else {
    EXPECT_GT(peak, reference.pressure);
  }
  EXPECT_GT(peak_ahead, 0.5 * elastic_pressure);
  EXPECT_LT(peak_ahead, 2.0 * elastic_pressure);
}

}  // namespace

// u_p = 200 m/s: partial compaction, the state behind the shock on the crush curve between P_e and P_s.
TEST(EnginePorousShock, PartialCompactionAt400MetresPerSecond) {
  check_porous_plates(400.0);
}

// u_p = 500 m/s: P above P_s, full compaction (alpha = 1) behind the shock.
TEST(EnginePorousShock, FullCompactionAt1000MetresPerSecond) {
  check_porous_plates(1000.0);
}
