// Planar impact of two Tillotson plates (aluminium on basalt, docs/physics.md section 2) against the
// impedance match of the two Tillotson Hugoniots, computed independently by root finding on the
// Rankine-Hugoniot conditions (tests/support/hugoniot.hpp): the mean pressure and particle
// velocity of the shocked target and projectile within 5 %.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "sph_core/engine_test_helpers.hpp"
#include "support/hugoniot.hpp"

using namespace craterkit::sph;
namespace ts = craterkit::test_support;

namespace {

void check_plates(double impact_velocity, int block_levels = 0) {
  StandardProblemConfig config;
  PlateImpactSetup setup;
  setup.impact_velocity = impact_velocity;
  setup.projectile_thickness = 0.02;
  setup.target_thickness = 0.04;
  setup.particle_spacing = 5e-4;
  config.problem = setup;
  config.simulation.solver.viscosity.viscosity_switch = ViscositySwitch::morris_monaghan;
  config.simulation.solver.time_step.block_levels = block_levels;
  if (block_levels > 0) config.simulation.solver.neighbours.search.skin = 0.1;
  const double end_time = 2.0e-6;
  config.simulation.run.end_time = end_time;
  auto sim = engine_test::run_to(config, end_time);

  const auto& materials = sim.materials();
  const auto match = ts::impedance_match(materials[0].eos, ts::InitialState{2700.0, 0.0}, materials[1].eos,
                                         ts::InitialState{2700.0, 0.0}, impact_velocity);
  // Shocked regions: between the contact and each shock front, away from both by a few particle
  // spacings (shock width and the start-up transient at the contact).
  const double contact = match.particle_velocity * end_time;
  const double target_front = match.target.shock_velocity * end_time;
  const double projectile_front = impact_velocity * end_time - match.projectile.shock_velocity * end_time;
  const double margin = 6.0 * setup.particle_spacing;
  double p_target = 0, u_target = 0, n_target = 0, p_projectile = 0, u_projectile = 0, n_projectile = 0;
  const auto& p = sim.particles();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.material[i] == 1 && p.x[i] > contact + margin && p.x[i] < target_front - margin) {
      p_target += p.pressure[i];
      u_target += p.vx[i];
      n_target += 1;
    }
    if (p.material[i] == 0 && p.x[i] > projectile_front + margin && p.x[i] < contact - margin) {
      p_projectile += p.pressure[i];
      u_projectile += p.vx[i];
      n_projectile += 1;
    }
  }
  ASSERT_GT(n_target, 0);
  ASSERT_GT(n_projectile, 0);
  p_target /= n_target;
  u_target /= n_target;
  p_projectile /= n_projectile;
  u_projectile /= n_projectile;
  std::printf(
      "plates %.0f m/s, block levels %d: match P %.4g GPa u %.4g m/s; target P %.4g GPa u %.4g m/s; "
      "projectile P %.4g GPa "
      "u %.4g m/s (%.0f + %.0f particles)\n",
      impact_velocity, block_levels, match.pressure * 1e-9, match.particle_velocity, p_target * 1e-9,
      u_target, p_projectile * 1e-9, u_projectile, n_target, n_projectile);
  EXPECT_NEAR(p_target / match.pressure, 1.0, 0.05);
  EXPECT_NEAR(u_target / match.particle_velocity, 1.0, 0.05);
  EXPECT_NEAR(p_projectile / match.pressure, 1.0, 0.05);
  EXPECT_NEAR(u_projectile / match.particle_velocity, 1.0, 0.05);
}

}  // namespace

TEST(PlateImpact, AluminiumOnBasaltAt2KilometresPerSecond) {
  check_plates(2000.0);
}

TEST(PlateImpact, AluminiumOnBasaltAt5KilometresPerSecond) {
  check_plates(5000.0);
}

// Block time steps (block_time_steps.hpp): the aluminium (c = 5.3 km/s) steps shorter than the basalt
// (3.1 km/s), and the shocked states sit on a lower level than the unshocked ones.
TEST(PlateImpact, AluminiumOnBasaltAt5KilometresPerSecondWithBlockTimeSteps) {
  check_plates(5000.0, 4);
}
