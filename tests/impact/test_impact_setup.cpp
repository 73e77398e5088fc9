// Impact scenario builder (impact_setup.hpp, docs/physics.md section 4): lattice, hemisphere, fixed shell,
// lithostatic state, projectile and its point-source stand-in, boulder shapes, quarter symmetry, the
// [impact] TOML table and the shipped examples.
//
// Independent references: lattice counts against the analytic volumes with a rigorous discretisation
// bound (every node's cell dx^3 lies within sqrt(3)/2 dx of the node, so the cells of the nodes inside a
// body of radius R cover the body shrunk by sqrt(3)/2 dx and lie inside it grown by the same amount);
// shapes against docs/physics.md's inequalities written out literally; the lithostatic profile against the
// hand value rho g depth and against a GSL ODE integration with the closed-form inverse of the cold
// Tillotson law; the stand-in against the point-source scaling law in both regimes.
#include <gtest/gtest.h>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "craterkit/common/toml_table.hpp"

#include "craterkit/common/data_path.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/impact/impact_config.hpp"
#include "craterkit/impact/impact_run.hpp"
#include "craterkit/impact/impact_setup.hpp"
#include "craterkit/impact/lithostatic.hpp"
#include "craterkit/sph/io/material_file.hpp"
#include "craterkit/sph/physics/material_response.hpp"

namespace craterkit::impact {
using namespace sph;
namespace {

// The run record of a set-up as snapshot attributes (impact_run_record.hpp).
RunAttributes record_attributes(const ImpactSummary& summary, KernelType kernel) {
  return run_record_attributes(make_run_record(summary, kernel, Particles{}, 0.0));
}

constexpr double pi = std::numbers::pi;
constexpr double eta = 1.2;
// A pressure derived from a density near the reference density is resolved only to A x (one ulp of
// rho_m / rho0) ~ 26.7 GPa x 2.2e-16 = 5.9e-6 Pa: the cold Tillotson law subtracts eta - 1. Under
// milligravity (P ~ 0.01-3 Pa) that, not the integration, limits the agreement of the particle pressures
// (evaluated from the particle densities, as the engine does) with rho g depth.
const double eos_resolution = 26.7e9 * std::numeric_limits<double>::epsilon();
const std::array<double, 3> ryugu_gravity{0.0, 0.0, -1.4e-4};

double hemisphere_volume(double r) {
  return 2.0 / 3.0 * pi * r * r * r;
}
double ball_volume(double r) {
  return 4.0 / 3.0 * pi * r * r * r;
}

ImpactSetup small_target(double radius, double spacing) {
  ImpactSetup s;
  s.domain_radius = radius;
  s.particle_spacing = spacing;
  return s;
}

std::size_t count_material(const Particles& p, std::uint16_t id) {
  return static_cast<std::size_t>(std::count(p.material.begin(), p.material.end(), id));
}

TEST(ImpactSetup, HemisphereCountMassAndTopLayer) {
  const double R = 3.0, dx = 0.1;
  const ImpactScenario sc = make_impact(small_target(R, dx), eta, 1.0, ryugu_gravity);
  const Particles& p = sc.problem.particles;
  const std::size_t n = count_material(p, 0);
  EXPECT_EQ(n, sc.summary.target_particles);
  // The cells tile z < 0 exactly (top layer at -dx/2), so only the curved boundary blurs the count.
  const double s = std::sqrt(3.0) / 2.0 * dx;
  const double cells = static_cast<double>(n) * dx * dx * dx;
  EXPECT_GT(cells, hemisphere_volume(R - s));
  EXPECT_LT(cells, hemisphere_volume(R + s));
  // Observed: 56,552 nodes for V/dx^3 = 56,548.7 (+0.006 %).
  EXPECT_NEAR(cells / hemisphere_volume(R), 1.0, 0.01);

  double mass = 0.0, top = -1e300, bottom = 1e300, r_max = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.material[i] != 0) continue;
    mass += p.mass[i];
    top = std::max(top, p.z[i]);
    bottom = std::min(bottom, p.z[i]);
    r_max = std::max(r_max, std::hypot(p.x[i], p.y[i], p.z[i]));
    EXPECT_EQ(p.distention[i], 2.0);
    EXPECT_EQ(p.specific_energy[i], 0.0);
    EXPECT_EQ(p.vx[i], 0.0);
    EXPECT_EQ(p.vz[i], 0.0);
    EXPECT_EQ(p.stress_xx[i], 0.0);
    EXPECT_DOUBLE_EQ(p.smoothing_length[i], eta * dx);
  }
  // Mass = bulk density 1300 kg/m^3 (2600 / alpha0 = 2) x node volume; the lithostatic compression under
  // milligravity is ~1e-10 (P ~ 0.5 Pa against A = 26.7 GPa).
  EXPECT_NEAR(mass / (1300.0 * cells), 1.0, 1e-9);
  EXPECT_DOUBLE_EQ(top, -0.5 * dx);
  EXPECT_LT(r_max, R);
  EXPECT_GT(bottom, -R);
  EXPECT_EQ(sc.summary.initial_bulk_density, 1300.0);
  EXPECT_FALSE(sc.problem.box.any_periodic());
}

TEST(ImpactSetup, FixedShellCoversTheKernelSupport) {
  const double R = 3.0, dx = 0.1;
  const ImpactScenario sc = make_impact(small_target(R, dx), eta, 1.0, ryugu_gravity);
  const Particles& p = sc.problem.particles;
  const double support = 2.0 * eta * dx;  // 2h: two smoothing lengths
  EXPECT_DOUBLE_EQ(sc.summary.fixed_shell_thickness, support);
  std::size_t fixed = 0;
  double r_fixed_min = 1e300, r_fixed_max = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r = std::hypot(p.x[i], p.y[i], p.z[i]);
    const bool is_fixed = (p.flags[i] & particle_fixed) != 0;
    if (p.material[i] == 1) {
      EXPECT_FALSE(is_fixed);
      continue;
    }
    if (is_fixed) {
      ++fixed;
      r_fixed_min = std::min(r_fixed_min, r);
      r_fixed_max = std::max(r_fixed_max, r);
    } else {
      // The whole kernel support of a moving particle lies inside the domain: it never sees the
      // missing material beyond the fixed shell.
      EXPECT_LE(r + p.smoothing_length[i] * 2.0, R + 1e-12) << i;
    }
  }
  EXPECT_EQ(fixed, sc.summary.fixed_particles);
  EXPECT_GT(r_fixed_min, R - support);
  EXPECT_LT(r_fixed_min, R - support + dx);  // the shell starts at R - 2h
  EXPECT_GT(r_fixed_max, R - dx);            // and reaches the domain edge
  // The shell's node count against the volume of the spherical shell R - 2h < r < R below z = 0, with
  // the same sqrt(3)/2 dx discretisation bound on both spheres.
  const double s = std::sqrt(3.0) / 2.0 * dx, v = dx * dx * dx;
  EXPECT_GT(fixed * v, hemisphere_volume(R - s) - hemisphere_volume(R - support + s));
  EXPECT_LT(fixed * v, hemisphere_volume(R + s) - hemisphere_volume(R - support - s));
}

TEST(ImpactSetup, LithostaticProfileUnderRyuguGravity) {
  const double R = 3.0, dx = 0.1;
  const ImpactScenario sc = make_impact(small_target(R, dx), eta, 1.0, ryugu_gravity);
  const Particles& p = sc.problem.particles;
  const Material& target = sc.problem.materials[0];
  std::map<int, double> by_layer;  // layer k -> pressure in the column at (dx/2, dx/2)
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.material[i] != 0 || std::abs(p.x[i] - 0.05) > 1e-9 || std::abs(p.y[i] - 0.05) > 1e-9) continue;
    const double depth = -p.z[i];
    // Hand value P = rho g depth, rho = 1300 kg/m^3, g = 1.4e-4 m/s^2: e.g. depth 2.35 m ->
    // 1300 x 1.4e-4 x 2.35 = 0.4277 Pa. Compression changes rho by P alpha0/A ~ 3e-11.
    EXPECT_NEAR(p.pressure[i], 1300.0 * 1.4e-4 * depth, 4.0 * eos_resolution) << depth;
    // The EOS gives that pressure back: P_m(alpha rho, 0)/alpha at the particle's state.
    const double eos = evaluate_material(target, p.density[i], 0.0, p.distention[i], 0.0).pressure;
    EXPECT_EQ(eos, p.pressure[i]) << depth;
    by_layer[static_cast<int>(std::lround(depth / dx - 0.5))] = p.pressure[i];
  }
  EXPECT_NEAR(by_layer.at(23), 0.4277, 4.0 * eos_resolution);  // depth 2.35 m
  EXPECT_NEAR(by_layer.at(0), 1300.0 * 1.4e-4 * 0.05, 4.0 * eos_resolution);
  EXPECT_NEAR(sc.summary.max_lithostatic_pressure, 1300.0 * 1.4e-4 * 2.95, 4.0 * eos_resolution);
}

// Reference for a strongly loaded target: dP/dd = g rho(P) with rho(P) = rho_m(alpha_c(P) P) / alpha_c(P)
// and the cold Tillotson law inverted in closed form, A chi + B chi^2 = P_m ->
// chi = (sqrt(A^2 + 4 B P_m) - A) / (2 B), integrated with GSL's rk8pd to 1e-12.
struct ColdPorous {
  double rho0, A, B, g;
  PAlphaParameters crush;
};

int reference_rate(double /*depth*/, const double y[], double dydt[], void* params) {
  const auto* m = static_cast<const ColdPorous*>(params);
  const double alpha = crush_curve_distention(m->crush, y[0]);
  const double pm = alpha * y[0];
  const double chi = 2.0 * pm / (m->A + std::sqrt(m->A * m->A + 4.0 * m->B * pm));  // stable form
  dydt[0] = m->g * m->rho0 * (1.0 + chi) / alpha;
  return GSL_SUCCESS;
}

TEST(ImpactSetup, LithostaticProfileThroughTheCrushCurve) {
  // g = 2000 m/s^2 in a 2 m target: P reaches ~5 MPa, beyond P_e = 1 MPa, so the deeper layers sit on
  // the crush curve (alpha < alpha0) and the density varies by ~25 %.
  const double R = 2.0, dx = 0.1, g = 2000.0;
  const ImpactScenario sc = make_impact(small_target(R, dx), eta, 1.0, {0.0, 0.0, -g});
  const Particles& p = sc.problem.particles;
  const Material& target = sc.problem.materials[0];
  const auto& till = std::get<Tillotson>(target.eos);
  ColdPorous model{till.reference_density, till.A, till.B, g, target.porosity->crush_curve};
  gsl_odeiv2_system system{reference_rate, nullptr, 1, &model};
  gsl_odeiv2_driver* driver = gsl_odeiv2_driver_alloc_y_new(&system, gsl_odeiv2_step_rk8pd, 1e-4, 1e-13, 0.0);
  std::vector<std::size_t> column;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.material[i] == 0 && std::abs(p.x[i] - 0.05) < 1e-9 && std::abs(p.y[i] - 0.05) < 1e-9)
      column.push_back(i);
  }
  std::sort(column.begin(), column.end(), [&](std::size_t a, std::size_t b) { return p.z[a] > p.z[b]; });
  ASSERT_EQ(column.size(), 20u);  // depths 0.05 ... 1.95 m (r < 2 m)
  double depth = 0.0, y[1] = {0.0};
  bool crushed = false;
  for (std::size_t i : column) {
    ASSERT_EQ(gsl_odeiv2_driver_apply(driver, &depth, -p.z[i], y), GSL_SUCCESS);
    // RK4 with two steps per half layer, split at the kink of alpha_c at P_e (at an estimated depth: the
    // remaining straddle leaves ~0.01 Pa, < 1e-8 relative; without the split it was 3 Pa).
    EXPECT_NEAR(p.pressure[i], y[0], 2e-8 * y[0]) << "depth " << -p.z[i];
    const double eos = evaluate_material(target, p.density[i], 0.0, p.distention[i], 0.0).pressure;
    EXPECT_NEAR(eos, p.pressure[i], 1e-9 * p.pressure[i]);
    EXPECT_NEAR(p.distention[i], crush_curve_distention(model.crush, p.pressure[i]), 1e-12);
    crushed = crushed || p.distention[i] < 1.9;
    EXPECT_DOUBLE_EQ(p.mass[i], p.density[i] * dx * dx * dx);
  }
  gsl_odeiv2_driver_free(driver);
  EXPECT_TRUE(crushed);
  EXPECT_GT(p.pressure[column.back()], 4e6);
}

TEST(ImpactSetup, SciStandInKeepsTheCouplingParameter) {
  ImpactSetup s;  // SCI defaults
  const ImpactSummary m = impact_projectile_summary(s, 2700.0);
  // a = (3 m / (4 pi delta))^(1/3) = (6 / (4 pi 2700))^(1/3) = 0.0561297 m (docs/physics.md: 5.6 cm).
  EXPECT_NEAR(m.projectile_radius, 0.0561297, 1e-7);
  EXPECT_EQ(m.model, ProjectileModel::point_source_stand_in);
  EXPECT_DOUBLE_EQ(m.model_radius, 2.0 * 0.25);  // max(a, 2 dx)
  // a delta^0.4 conserved; delta_s = 2700 (0.0561297/0.5)^2.5 = 11.4004 kg/m^3.
  EXPECT_NEAR(m.model_radius * std::pow(m.model_density, 0.4) / (m.projectile_radius * std::pow(2700.0, 0.4)),
              1.0, 1e-13);
  EXPECT_NEAR(m.model_density, 11.4004, 1e-4);
  // Mass, momentum and energy all grow by (a_s/a)^(3 - 1/nu) = sqrt(0.5 / 0.0561297) = 2.98462.
  EXPECT_NEAR(m.model_mass / m.projectile_mass, std::sqrt(0.5 / m.projectile_radius), 1e-12);
  EXPECT_NEAR(m.model_mass, 5.96924, 1e-5);
  EXPECT_NEAR(m.model_density_scale, 11.4004 / 2700.0, 1e-7);
  // The point-source law (docs/physics.md section 6, Housen & Holsapple form, jutzi2022_ryugu mu = 0.44)
  // gives the same crater for both projectiles in the gravity and in the strength regime.
  const double mu = 0.44, nu = 0.4, H1 = 0.6, H2 = 0.25, rho = 1300.0, U = 2000.0, g = 1.4e-4, Y = 1e3;
  auto gravity_radius = [&](double a, double delta) {
    const double mass = 4.0 / 3.0 * pi * a * a * a * delta;
    return H1 * std::pow(g * a / (U * U), -mu / (2 + mu)) *
           std::pow(rho / delta, (2 + mu - 6 * nu) / (3 * (2 + mu))) * std::cbrt(mass / rho);
  };
  auto strength_radius = [&](double a, double delta) {
    const double mass = 4.0 / 3.0 * pi * a * a * a * delta;
    return H2 * std::pow(Y / (rho * U * U), -mu / 2) * std::pow(rho / delta, (1 - 3 * nu) / 3) *
           std::cbrt(mass / rho);
  };
  EXPECT_NEAR(gravity_radius(m.model_radius, m.model_density) / gravity_radius(m.projectile_radius, 2700.0),
              1.0, 1e-12);
  EXPECT_NEAR(strength_radius(m.model_radius, m.model_density) / strength_radius(m.projectile_radius, 2700.0),
              1.0, 1e-12);
  // A stand-in of the same MASS and the same radius a_s makes a much smaller crater (docs/physics.md).
  const double same_mass_density = 2.0 / ball_volume(0.5);
  EXPECT_LT(gravity_radius(0.5, same_mass_density) / gravity_radius(m.projectile_radius, 2700.0), 0.7);
}

TEST(ImpactSetup, StandInParticlesMassVelocityAndPosition) {
  ImpactSetup s = small_target(3.0, 0.25);
  s.impact_angle = 30.0;
  const ImpactScenario sc = make_impact(s, eta, 1.0, ryugu_gravity);
  const Particles& p = sc.problem.particles;
  const ImpactSummary& m = sc.summary;
  double mass = 0.0, px = 0.0, pz = 0.0, kinetic = 0.0, lowest = 1e300;
  std::array<double, 3> centre{0.0, 0.0, 0.0};
  std::size_t n = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.material[i] != 1) continue;
    ++n;
    mass += p.mass[i];
    px += p.mass[i] * p.vx[i];
    pz += p.mass[i] * p.vz[i];
    kinetic += 0.5 * p.mass[i] * (p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
    centre[0] += p.mass[i] * p.x[i];
    centre[1] += p.mass[i] * p.y[i];
    centre[2] += p.mass[i] * p.z[i];
    lowest = std::min(lowest, p.z[i]);
    EXPECT_DOUBLE_EQ(p.density[i], m.model_density);
    EXPECT_NEAR(p.pressure[i], 0.0, 1e-6);  // at the scaled material's reference density, E = 0
  }
  EXPECT_EQ(n, 32u);  // offset lattice in a sphere of radius 2 dx: 8 + 24 nodes
  EXPECT_EQ(n, m.projectile_particles);
  EXPECT_NEAR(mass, m.model_mass, 1e-12 * mass);
  // U (sin 30, 0, -cos 30) = (1000, 0, -1732.05) m/s.
  EXPECT_NEAR(px / mass, 1000.0, 1e-9);
  EXPECT_NEAR(pz / mass, -2000.0 * std::sqrt(3.0) / 2.0, 1e-9);
  EXPECT_NEAR(kinetic, 0.5 * m.model_mass * 4e6, 1e-6 * kinetic);
  // Centre (0, 0, a_s): the sphere touches z = 0 at the impact point; its lowest layer is at
  // a_s - 1.5 dx = +dx/2, one spacing above the top target layer at -dx/2.
  EXPECT_NEAR(centre[0] / mass, 0.0, 1e-12);
  EXPECT_NEAR(centre[1] / mass, 0.0, 1e-12);
  EXPECT_NEAR(centre[2] / mass, 0.5, 1e-12);
  EXPECT_NEAR(lowest, 0.125, 1e-12);
  // The stand-in material: the aluminium law with density and stresses scaled by k.
  const Material& al = sc.problem.materials[1];
  EXPECT_NEAR(std::get<Tillotson>(al.eos).reference_density, m.model_density, 1e-9);
  EXPECT_EQ(al.name, "aluminium_projectile_stand_in");
}

TEST(ImpactSetup, DensityScaledMaterialHasTheSameHugoniotInVelocitySpace) {
  const Material al = load_material("aluminium_projectile");
  const double k = 0.01;
  const Material scaled = density_scaled_material(al, k);
  for (const double eta_c : {0.9, 1.0, 1.1, 1.4}) {
    for (const double e : {0.0, 1e6, 5e6, 2e7}) {
      const double rho = 2700.0 * eta_c;
      const MaterialState a = evaluate_material(al, rho, e, 1.0, 0.0);
      const MaterialState b = evaluate_material(scaled, k * rho, e, 1.0, 0.0);
      EXPECT_NEAR(b.pressure, k * a.pressure, 1e-9 * std::abs(k * a.pressure) + 1e-9);
      EXPECT_NEAR(b.sound_speed, a.sound_speed, 1e-9 * a.sound_speed);
      EXPECT_NEAR(b.yield_strength, k * a.yield_strength, 1e-6);
      EXPECT_NEAR(b.shear_modulus / (k * rho), a.shear_modulus / rho, 1e-9 * a.shear_modulus / rho);
    }
  }
}

TEST(ImpactSetup, ResolvedProjectile) {
  ImpactSetup s = small_target(1.0, 0.02);
  s.projectile_model = ProjectileModel::resolved;
  const ImpactScenario sc = make_impact(s, eta, 1.0, ryugu_gravity);
  const Particles& p = sc.problem.particles;
  double mass = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.material[i] == 1) mass += p.mass[i];
  }
  EXPECT_NEAR(mass, 2.0, 1e-12);
  const std::size_t n = count_material(p, 1);
  const double a = sc.summary.projectile_radius, sphalf = std::sqrt(3.0) / 2.0 * 0.02;
  EXPECT_GT(n * 8e-6, ball_volume(a - sphalf));
  EXPECT_LT(n * 8e-6, ball_volume(a + sphalf));
  EXPECT_DOUBLE_EQ(sc.summary.model_density_scale, 1.0);
  EXPECT_EQ(sc.problem.materials[1].name, "aluminium_projectile");
  // Unresolvable at dx = 0.25 m: the error names the spacing and the way out.
  ImpactSetup coarse;
  coarse.projectile_model = ProjectileModel::resolved;
  try {
    (void)impact_projectile_summary(coarse, 2700.0);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("impact.particle_spacing"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("point_source_stand_in"), std::string::npos) << e.what();
  }
}

TEST(ImpactSetup, QuarterSymmetryIsAQuarterOfTheFullDomain) {
  ImpactSetup s = small_target(2.0, 0.1);
  const ImpactScenario full = make_impact(s, eta, 1.0, ryugu_gravity);
  s.symmetry = DomainSymmetry::quarter;
  const ImpactScenario quarter = make_impact(s, eta, 1.0, ryugu_gravity);
  const Particles& q = quarter.problem.particles;
  for (std::size_t i = 0; i < q.size(); ++i) {
    ASSERT_GE(q.x[i], 0.0);
    ASSERT_GE(q.y[i], 0.0);
  }
  EXPECT_EQ(4 * quarter.summary.target_particles, full.summary.target_particles);
  EXPECT_EQ(4 * quarter.summary.fixed_particles, full.summary.fixed_particles);
  EXPECT_EQ(4 * quarter.summary.projectile_particles, full.summary.projectile_particles);
  // Full sphere mass recorded; the quarter holds a quarter of it.
  double mass = 0.0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    if (q.material[i] == 1) mass += q.mass[i];
  }
  EXPECT_NEAR(4.0 * mass, quarter.summary.model_mass, 1e-12);
  EXPECT_EQ(record_attributes(quarter.summary, KernelType::cubic_spline).texts.at("symmetry"), "quarter");
  // The planes x = 0 and y = 0 are mirror planes of the quarter's box, and only of the quarter's.
  const Box& box = quarter.problem.box;
  EXPECT_TRUE(box.mirror[0] && box.mirror[1] && !box.mirror[2]);
  EXPECT_EQ(box.lower[0], 0.0);
  EXPECT_EQ(box.lower[1], 0.0);
  EXPECT_FALSE(full.problem.box.any_mirror());
  EXPECT_NE(describe_impact(quarter.summary).find("mirror planes x = 0, y = 0"), std::string::npos);
  // Oblique impacts and boulders break the mirror symmetry.
  s.impact_angle = 10.0;
  EXPECT_THROW((void)make_impact(s, eta, 1.0, ryugu_gravity), InputError);
  s.impact_angle = 0.0;
  s.boulders.push_back({"1", "boulder", Shape{{Sphere{{1.0, 1.0, -1.0}, 0.3}}}});
  EXPECT_THROW((void)make_impact(s, eta, 1.0, ryugu_gravity), InputError);
}

TEST(ImpactSetup, SphereBoulderHoldsTheRightParticles) {
  ImpactSetup s = small_target(4.0, 0.1);
  const Sphere ball{{0.4, -0.3, -1.5}, 1.0};
  s.boulders.push_back({"deep", "boulder", Shape{{ball}}});
  const ImpactScenario sc = make_impact(s, eta, 1.0, ryugu_gravity);
  const Particles& p = sc.problem.particles;
  const std::size_t n = count_material(p, 2);
  EXPECT_EQ(n, sc.summary.boulder_particles.at(0));
  const double sh = std::sqrt(3.0) / 2.0 * 0.1;
  EXPECT_GT(n * 1e-3, ball_volume(1.0 - sh));
  EXPECT_LT(n * 1e-3, ball_volume(1.0 + sh));
  EXPECT_NEAR(n * 1e-3 / ball_volume(1.0), 1.0, 0.01);  // observed 4,224 for 4,188.8 (+0.8 %)
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double d = std::hypot(p.x[i] - 0.4, p.y[i] + 0.3, p.z[i] + 1.5);
    EXPECT_EQ(p.material[i] == 2, d < 1.0) << i;
    if (p.material[i] == 2) {
      EXPECT_EQ(p.distention[i], 1.0);  // no porosity
      // Boulder rho0 = 1300: the lithostatic pressure above it barely compresses it.
      EXPECT_NEAR(p.density[i], 1300.0, 1e-6);
    }
  }
  // Pressure continuity through the boulder (same bulk density as the matrix): rho g depth again.
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.material[i] == 1) continue;
    EXPECT_NEAR(p.pressure[i], 1300.0 * 1.4e-4 * (-p.z[i]), 4.0 * eos_resolution);
  }
  // The run record tracks the boulder by its material id, from its mass-weighted centre at t = 0.
  const auto record = make_run_record(sc.summary, KernelType::cubic_spline, p, 0.0);
  ASSERT_EQ(record.boulders.size(), 1u);
  EXPECT_NEAR(record.boulders[0].initial_centre[0], 0.4, 0.02);
  EXPECT_NEAR(record.boulders[0].initial_centre[2], -1.5, 0.02);
  EXPECT_EQ(record.boulders[0].material, 2);
  const auto specs = crater_measurement_options(record).boulders;
  ASSERT_EQ(specs.size(), 1u);
  EXPECT_EQ(specs[0].material, 2);
  EXPECT_EQ(specs[0].initial_centre, record.boulders[0].initial_centre);
  // Through the snapshot attributes and back, exactly.
  const auto back = read_run_record(run_record_attributes(record), "test");
  ASSERT_EQ(back.boulders.size(), 1u);
  EXPECT_EQ(back.boulders[0].name, record.boulders[0].name);
  EXPECT_EQ(back.boulders[0].initial_centre, record.boulders[0].initial_centre);
}

// The [impact] table of a shipped example.
ImpactSetup example_setup(const std::string& file) {
  const std::string path = data_file("examples/" + file).string();
  TomlTable root = TomlTable::parse_file(path);
  EXPECT_EQ(root.table("problem").text("setup", ""), "impact") << file;
  return parse_impact_setup(root.table("impact"));
}

TEST(ImpactSetup, PhysicsMdBouldersFromTheExample) {
  ImpactSetup s = example_setup("sci-boulders.toml");
  ASSERT_EQ(s.boulders.size(), 4u);
  // A uniform lattice coarser than the example's graded target, to keep the test fast (56 k particles) and
  // the nodes countable below; the stand-in takes the place of the unresolved projectile.
  s.particle_spacing = 0.5;
  s.inner_spacing = 0.0;
  s.projectile_model = ProjectileModel::point_source_stand_in;
  const ImpactScenario sc = make_impact(s, eta, 1.0, ryugu_gravity);
  const Particles& p = sc.problem.particles;
  const double dx = 0.5;
  // Every node is where docs/physics.md's table says, written out literally here.
  auto boulder_of = [](double x, double y, double z) -> int {
    auto sphere = [&](double cx, double cy, double cz, double r) {
      return (x - cx) * (x - cx) + (y - cy) * (y - cy) + (z - cz) * (z - cz) < r * r;
    };
    if (sphere(2.5, 0.0, 0.0, 1.0)) return 1;
    if (sphere(0.5, -2.0, 0.0, 1.0)) return 2;
    if (sphere(1.0, 3.5, 0.0, 2.5)) return 3;
    if (std::sqrt(x * x + y * y) < 9 && x < -2 && std::abs(y) < 5 && -5 < z && z < 0.5) return 4;
    return 0;
  };
  std::array<std::size_t, 5> expected{};
  for (long i = -40; i < 40; ++i) {
    for (long j = -40; j < 40; ++j) {
      for (long k = -40; k < 40; ++k) {
        const double x = (i + 0.5) * dx, y = (j + 0.5) * dx, z = -(k + 0.5) * dx;
        if (x * x + y * y + z * z >= 15.0 * 15.0) continue;
        const int b = boulder_of(x, y, z);
        if (b > 0 || z < 0.0) ++expected[static_cast<std::size_t>(b)];
      }
    }
  }
  for (std::size_t b = 0; b < 4; ++b) {
    EXPECT_EQ(sc.summary.boulder_particles[b], expected[b + 1]) << "boulder " << b + 1;
    EXPECT_EQ(count_material(p, static_cast<std::uint16_t>(2 + b)), expected[b + 1]);
    EXPECT_EQ(sc.summary.boulder_names[b], std::to_string(b + 1));
  }
  EXPECT_EQ(sc.summary.target_particles, expected[0]);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.material[i] == 1) continue;
    const int b = boulder_of(p.x[i], p.y[i], p.z[i]);
    ASSERT_EQ(static_cast<int>(p.material[i]), b == 0 ? 0 : b + 1) << i;
  }
  // Block 4's volume: 5.5 m x area{x^2 + y^2 < 81, x < -2, |y| < 5} = 5.5 (5 sqrt(56) + 81 asin(5/9) - 20)
  // = 5.5 x 65.128 = 358.2 m^3; the node count at dx = 0.5 is within 5 % of it (coarse lattice).
  EXPECT_NEAR(
      expected[4] * dx * dx * dx / (5.5 * (5.0 * std::sqrt(56.0) + 81.0 * std::asin(5.0 / 9.0) - 20.0)), 1.0,
      0.05);
  // Spheres 1-3 stick out of the surface: their nodes above z = 0 exist.
  bool above = false;
  for (std::size_t i = 0; i < p.size(); ++i) above = above || (p.material[i] == 4 && p.z[i] > 0.0);
  EXPECT_TRUE(above);
  const RunAttributes attributes = record_attributes(sc.summary, KernelType::cubic_spline);
  EXPECT_EQ(attributes.numbers.at("boulder_4_material"), 5.0);
}

TEST(ImpactSetup, RunAttributesForTheMeasurement) {
  const ImpactScenario sc = make_impact(small_target(3.0, 0.25), eta, 1.0, ryugu_gravity);
  const RunAttributes a = record_attributes(sc.summary, KernelType::wendland_c2);
  EXPECT_EQ(a.numbers.at("initial_bulk_density"), 1300.0);
  EXPECT_EQ(a.numbers.at("particle_spacing"), 0.25);
  EXPECT_EQ(a.texts.at("kernel"), "wendland_c2");
  EXPECT_EQ(a.texts.at("symmetry"), "full");
  EXPECT_EQ(a.texts.at("projectile_model"), "point_source_stand_in");
  // t_transition = 10 R_dom / c, c = 1500 m/s (porous_sound_speed of basalt_matrix_ryugu at alpha0).
  EXPECT_NEAR(a.numbers.at("t_transition"), 10.0 * 3.0 / 1500.0, 1e-12);
  EXPECT_EQ(a.numbers.at("A_low"), 0.027e6);
  EXPECT_NEAR(a.numbers.at("projectile_radius"), 0.0561297, 1e-7);
  EXPECT_EQ(a.numbers.at("projectile_mass"), 2.0);
  EXPECT_EQ(a.numbers.at("impact_speed"), 2000.0);
  EXPECT_EQ(a.numbers.at("stand_in_radius"), 0.5);
  EXPECT_NEAR(a.numbers.at("stand_in_mass"), 5.96924, 1e-5);
  EXPECT_NEAR(a.numbers.at("stand_in_density_scale"), 11.4004 / 2700.0, 1e-7);
  // SCI: 10 x 15 m / 1500 m/s = 0.1 s, docs/physics.md's value.
  ImpactSetup sci;
  sci.particle_spacing = 1.0;
  EXPECT_NEAR(make_impact(sci, eta, 1.0, ryugu_gravity).summary.transition_time, 0.1, 1e-12);
  sci.transition_time = 0.3;
  const ImpactScenario given = make_impact(sci, eta, 1.0, ryugu_gravity);
  EXPECT_EQ(given.summary.transition_time, 0.3);
  EXPECT_NE(describe_impact(given.summary).find("(given)"), std::string::npos);
}

std::string parse_error(const std::string& text) {
  try {
    (void)parse_impact_setup(TomlTable::parse(text, "test.toml").table("impact"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ImpactSetup, TomlErrorsNameTheKey) {
  EXPECT_NE(parse_error("[impact]\nprojectile_mas = 2.0\n").find("unknown key impact.projectile_mas"),
            std::string::npos);
  EXPECT_NE(parse_error("[impact]\nimpact_speed = \"fast\"\n").find("impact.impact_speed: expected a number"),
            std::string::npos);
  EXPECT_NE(
      parse_error("[impact]\ndomain_radius = -1.0\n").find("impact.domain_radius: value -1 out of range"),
      std::string::npos);
  EXPECT_NE(
      parse_error("[impact]\nsymmetry = \"half\"\n").find("impact.symmetry: value \"half\" not allowed"),
      std::string::npos);
  EXPECT_NE(parse_error("[impact]\nimpact_angle = 95\n").find("impact.impact_angle"), std::string::npos);
  EXPECT_NE(parse_error("[impact]\nparticle_spacing = 3.0\n").find("impact.particle_spacing"),
            std::string::npos);
  EXPECT_NE(parse_error("[impact]\nsymmetry = \"quarter\"\nimpact_angle = 30\n").find("impact.symmetry"),
            std::string::npos);
  EXPECT_NE(parse_error("[impact]\n[[impact.boulders]]\nshape = \"sphere\"\ncentre = [0, 0, 0]\n")
                .find("impact.boulders[0].radius: missing"),
            std::string::npos);
  EXPECT_NE(parse_error("[impact]\n[[impact.boulders]]\nshape = \"cube\"\n").find("impact.boulders[0].shape"),
            std::string::npos);
  EXPECT_NE(parse_error("[impact]\n[[impact.boulders]]\nshape = \"sphere\"\ncentre = [0, 0]\nradius = 1\n")
                .find("impact.boulders[0].centre: expected 3 numbers"),
            std::string::npos);
  EXPECT_NE(
      parse_error("[impact]\n[[impact.boulders]]\n[[impact.boulders.parts]]\nshape = \"cylinder\"\naxis = "
                  "[0, 0]\nradius = 9\n[[impact.boulders.parts]]\nshape = \"half_space\"\nnormal = [1, 0, "
                  "0]\noffset = -2\ncolour = \"grey\"\n")
          .find("unknown key impact.boulders[0].parts[1].colour"),
      std::string::npos);
  EXPECT_NE(
      parse_error("[impact]\n[[impact.boulders]]\nname = \"a\"\nshape = \"sphere\"\ncentre = [0, 0, -3]\n"
                  "radius = 1\n[[impact.boulders]]\nname = \"a\"\nshape = \"sphere\"\ncentre = [0, 0, -6]\n"
                  "radius = 1\n")
          .find("impact.boulders[1].name"),
      std::string::npos);
  EXPECT_NE(parse_error("[impact]\ntensile_porosity = 1\n").find("impact.tensile_porosity"),
            std::string::npos);
  EXPECT_FALSE(
      parse_impact_setup(TomlTable::parse("[impact]\n", "test.toml").table("impact")).tensile_porosity);
  EXPECT_TRUE(
      parse_impact_setup(TomlTable::parse("[impact]\ntensile_porosity = true\n", "test.toml").table("impact"))
          .tensile_porosity);
  // The error-free default table gives the SCI defaults.
  EXPECT_EQ(parse_error("[impact]\n"), "");
}

TEST(ImpactSetup, MakeImpactRejectsImpossibleSetups) {
  auto message = [](const ImpactSetup& s, std::array<double, 3> g) -> std::string {
    try {
      (void)make_impact(s, eta, 1.0, g);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message(small_target(3.0, 0.25), {1e-4, 0.0, -1.4e-4}).find("run.gravity"), std::string::npos);
  ImpactSetup s = small_target(3.0, 0.25);
  s.boulders.push_back({"on_top", "boulder", Shape{{Sphere{{0.0, 0.0, 0.0}, 0.6}}}});
  EXPECT_NE(message(s, ryugu_gravity).find("impact.boulders[0]: overlaps the projectile"), std::string::npos);
  s.boulders.clear();
  s.stand_in_radius = 0.3;  // below 2 dx = 0.5
  EXPECT_NE(message(s, ryugu_gravity).find("impact.stand_in_radius"), std::string::npos);
  s.stand_in_radius = 0.0;
  s.fixed_shell_thickness = 0.3;  // below 2 h = 0.6
  EXPECT_NE(message(s, ryugu_gravity).find("impact.fixed_shell_thickness"), std::string::npos);
  s.fixed_shell_thickness = 0.0;
  s.target_material = "ideal_gas_monatomic";
  EXPECT_NE(message(s, ryugu_gravity).find("impact.target_material"), std::string::npos);
}

TEST(ImpactSetup, ShippedExamplesParse) {
  for (const char* file :
       {"sci.toml", "sci-boulders.toml", "impact-0.05kg.toml", "impact-100kg.toml", "impact-2000kg.toml"}) {
    const ImpactSetup s = example_setup(file);
    // Domain and outer spacing scaled together: R_dom / dx_max = 30 in every example (sci.toml's 15 / 0.5).
    EXPECT_NEAR(s.domain_radius / s.particle_spacing, 30.0, 0.05) << file;
    // The projectile resolved at its own density on a graded target, dx0 <= a/2 (within 3 %).
    const ImpactSummary m = impact_projectile_summary(s, 2700.0);
    EXPECT_EQ(m.model, ProjectileModel::resolved) << file;
    EXPECT_EQ(m.model_density, 2700.0) << file;
    EXPECT_GT(s.inner_spacing, 0.0) << file;
    EXPECT_LE(s.inner_spacing, 0.5 * m.projectile_radius) << file;
    EXPECT_GT(s.inner_spacing, 0.97 * 0.5 * m.projectile_radius) << file;
    EXPECT_EQ(s.symmetry, s.boulders.empty() ? DomainSymmetry::quarter : DomainSymmetry::full) << file;
  }
}

}  // namespace
}  // namespace craterkit::impact
