// Longitudinal elastic wave in a solid (docs/physics.md section 2): the deviatoric stress of
// Hooke's law with the Jaumann rate makes a compression front travel at
//   c_L = sqrt((K + 4/3 G) / rho0)        (uniaxial strain)
// instead of the bulk sound speed sqrt(K/rho0). Aluminium Tillotson near rho0 and E = 0 has K = A.
// Set-up: a long bar, periodic along all three axes (so the strain is uniaxial: the cross-section
// cannot expand), whose two halves approach each other at +-v0. Two compression fronts leave the centre;
// the front position (where the mean velocity of a lattice plane has fallen half-way from -v0 to 0) is
// fitted against time by least squares, so the start-up offset of the smoothed front drops out.
// v0 = 1 m/s gives sqrt(J2) ~ 10 MPa, far below the von Mises Y = 0.34 GPa: the bar stays elastic.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string_view>
#include <type_traits>
#include <vector>

#include "craterkit/sph/io/config.hpp"
#include "craterkit/sph/io/material_file.hpp"
#include "craterkit/sph/physics/deviatoric_stress.hpp"
#include "craterkit/sph/physics/material.hpp"
#include "craterkit/sph/run/standard_problem_config.hpp"
#include "craterkit/sph/solver/simulation.hpp"
#include "sph_core/engine_test_helpers.hpp"

namespace {

using namespace craterkit::sph;

constexpr int bar_planes = 200;   // lattice planes along x
constexpr int cross_section = 6;  // lattice cells across y and z
constexpr double spacing = 1e-3;  // m
constexpr double v0 = 1.0;        // m/s, each half towards the centre

ProblemSetup make_bar(const Material& material, double eta, double alpha) {
  ProblemSetup problem;
  problem.materials = {material};
  const double rho0 = std::get<Tillotson>(material.eos).reference_density;
  const double length = bar_planes * spacing;
  const double width = cross_section * spacing;
  problem.box.lower = {-0.5 * length, 0.0, 0.0};
  problem.box.upper = {0.5 * length, width, width};
  problem.box.periodic = {true, true, true};
  auto& p = problem.particles;
  p.resize(static_cast<std::size_t>(bar_planes) * cross_section * cross_section);
  std::size_t k = 0;
  for (int i = 0; i < bar_planes; ++i) {
    for (int j = 0; j < cross_section; ++j) {
      for (int l = 0; l < cross_section; ++l, ++k) {
        p.id[k] = k;
        p.x[k] = -0.5 * length + (i + 0.5) * spacing;
        p.y[k] = (j + 0.5) * spacing;
        p.z[k] = (l + 0.5) * spacing;
        p.vx[k] = p.x[k] < 0.0 ? v0 : -v0;
        p.mass[k] = rho0 * spacing * spacing * spacing;
        p.density[k] = rho0;
        p.smoothing_length[k] = eta * spacing;
        p.viscosity_alpha[k] = alpha;
      }
    }
  }
  return problem;
}

// Distance from the centre of the front on the side x > 0 (sign = +1) or x < 0 (sign = -1): the first
// plane, going outwards, whose mean velocity towards the centre has fallen below v0/2, interpolated.
double front_distance(const Particles& p, int sign) {
  std::vector<double> sum(bar_planes, 0.0);
  std::vector<int> count(bar_planes, 0);
  for (std::size_t k = 0; k < p.size(); ++k) {
    const int plane = static_cast<int>(std::floor(p.x[k] / spacing + 0.5 * bar_planes));
    if (plane < 0 || plane >= bar_planes) continue;
    sum[plane] += p.vx[k];
    ++count[plane];
  }
  double previous_distance = 0.0, previous_inflow = 0.0;
  for (int step = 0; step < bar_planes / 2; ++step) {
    const int plane = sign > 0 ? bar_planes / 2 + step : bar_planes / 2 - 1 - step;
    if (count[plane] == 0) continue;
    const double inflow = -sign * sum[plane] / count[plane];  // velocity towards the centre
    const double distance = (step + 0.5) * spacing;
    if (inflow > 0.5 * v0) {
      if (step == 0) return distance;
      return previous_distance +
             (0.5 * v0 - previous_inflow) / (inflow - previous_inflow) * (distance - previous_distance);
    }
    previous_distance = distance;
    previous_inflow = inflow;
  }
  return NAN;
}

struct Measurement {
  double speed;             // m/s, fitted front speed
  double max_shear_stress;  // max sqrt(J2) at the end, Pa
  bool solid_fields;        // the particles held the solid-mechanics group
};

Measurement measure_front_speed(const Material& material) {
  const double c_longitudinal =
      std::sqrt((std::get<Tillotson>(material.eos).A + 4.0 / 3.0 * material.shear_modulus) /
                std::get<Tillotson>(material.eos).reference_density);
  StandardProblemConfig config;
  Simulation sim(config.simulation.solver, make_bar(material, config.simulation.solver.smoothing.eta,
                                                    config.simulation.solver.viscosity.alpha));

  // Fronts from the centre and from the periodic ends meet at a quarter of the bar, t = L / (4 c_L)
  // (c_L is the fastest wave either material can carry).
  const double meet = bar_planes * spacing / (4.0 * c_longitudinal);
  std::vector<double> times, fronts;
  for (int k = 1; k <= 8; ++k) {
    const double t = meet * (0.15 + 0.1 * k);  // 0.25 .. 0.95 of the meeting time
    while (sim.time() < t) sim.step(t);
    times.push_back(t);
    fronts.push_back(0.5 * (front_distance(sim.particles(), +1) + front_distance(sim.particles(), -1)));
  }
  double mt = 0, mf = 0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    mt += times[k] / times.size();
    mf += fronts[k] / times.size();
  }
  double stt = 0, stf = 0;
  for (std::size_t k = 0; k < times.size(); ++k) {
    stt += (times[k] - mt) * (times[k] - mt);
    stf += (times[k] - mt) * (fronts[k] - mf);
  }
  const auto& p = sim.particles();
  double max_j2 = 0.0;
  for (std::size_t k = 0; p.solid_fields && k < p.size(); ++k) {
    const double j2 = second_invariant(
        DeviatoricStress{p.stress_xx[k], p.stress_xy[k], p.stress_xz[k], p.stress_yy[k], p.stress_yz[k]});
    max_j2 = std::max(max_j2, j2);
  }
  return Measurement{stf / stt, std::sqrt(max_j2), p.solid_fields};
}

TEST(EngineElasticWave, LongitudinalFrontTravelsAtElasticWaveSpeed) {
  const Material aluminium = load_material("aluminium_projectile");
  ASSERT_TRUE(aluminium.strength.has_value());
  const auto& eos = std::get<Tillotson>(aluminium.eos);
  const double c_longitudinal =
      std::sqrt((eos.A + 4.0 / 3.0 * aluminium.shear_modulus) / eos.reference_density);
  const Measurement m = measure_front_speed(aluminium);
  std::printf("elastic wave (aluminium_projectile): measured %.1f m/s, c_L %.1f m/s, error %+.2f %%\n",
              m.speed, c_longitudinal, 100.0 * (m.speed / c_longitudinal - 1.0));
  EXPECT_NEAR(m.speed / c_longitudinal, 1.0, 0.05);
  // The bar stayed elastic: sqrt(J2) well below the yield strength (radial return inactive).
  EXPECT_GT(m.max_shear_stress, 0.0);
  EXPECT_LT(m.max_shear_stress, 0.1 * std::get<VonMisesStrength>(*aluminium.strength).yield_strength);
}

// Control: the same law without [strength] is a fluid; its front travels at the bulk sound speed
// sqrt(A/rho0), 18 % slower than c_L, and carries no deviatoric stress.
TEST(EngineElasticWave, FluidFrontTravelsAtBulkSoundSpeed) {
  const Material aluminium = load_material("aluminium");
  ASSERT_FALSE(aluminium.strength.has_value());
  const auto& eos = std::get<Tillotson>(aluminium.eos);
  const double c_bulk = std::sqrt(eos.A / eos.reference_density);
  const Measurement m = measure_front_speed(aluminium);
  std::printf("fluid wave (aluminium): measured %.1f m/s, bulk c %.1f m/s, error %+.2f %%\n", m.speed, c_bulk,
              100.0 * (m.speed / c_bulk - 1.0));
  EXPECT_NEAR(m.speed / c_bulk, 1.0, 0.05);
  EXPECT_EQ(m.max_shear_stress, 0.0);
  EXPECT_FALSE(m.solid_fields);  // a fluid run does not even allocate the stress fields
}

// A yielding solid (Y lowered to 1 MPa, halves at +-20 m/s: the radial return is active) continued from
// its state after 15 steps, as a checkpoint restart does, ends bit-for-bit where the uninterrupted run
// ends: the stress rates are particle fields and the radial return of the restarted constructor leaves
// an already returned stress unchanged.
TEST(EngineElasticWave, YieldingSolidRestartIsBitwise) {
  Material material = load_material("aluminium_projectile");
  material.strength = VonMisesStrength{1e6};
  StandardProblemConfig config;
  auto problem =
      make_bar(material, config.simulation.solver.smoothing.eta, config.simulation.solver.viscosity.alpha);
  for (auto& v : problem.particles.vx) v *= 20.0;
  const auto restart_problem = problem;
  Simulation straight(config.simulation.solver, std::move(problem));
  for (int k = 0; k < 15; ++k) straight.step(1.0);
  straight.force_neighbour_rebuild();  // as after writing a checkpoint
  Simulation resumed(config.simulation.solver, restart_problem, straight.particles(), straight.state());
  for (int k = 0; k < 15; ++k) {
    straight.step(1.0);
    resumed.step(1.0);
  }
  EXPECT_EQ(straight.time(), resumed.time());
  EXPECT_EQ(straight.next_time_step(), resumed.next_time_step());
  double max_j2_ratio = 0.0;
  const auto& a = straight.particles();
  const auto& b = resumed.particles();
  for (std::size_t k = 0; k < a.size(); ++k) {
    const double j2 = second_invariant(
        DeviatoricStress{a.stress_xx[k], a.stress_xy[k], a.stress_xz[k], a.stress_yy[k], a.stress_yz[k]});
    max_j2_ratio = std::max(max_j2_ratio, std::sqrt(j2) / 1e6);
  }
  EXPECT_NEAR(max_j2_ratio, 1.0, 1e-9);  // some particles sit on the yield surface
  engine_test::expect_identical_particles(a, b);
}

}  // namespace
