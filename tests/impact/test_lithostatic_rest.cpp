// A target in lithostatic equilibrium under gravity stays at rest, before and after the low-sound-speed
// transition: over 20 sound-crossing times L / c the largest speed stays below 1e-3 of the
// free-fall speed sqrt(g L) and the surface moves less than 0.05 particle spacings. The target is the
// impact set-up's hemisphere (make_impact through the engine's scenario) without its projectile.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "craterkit/impact/impact_run.hpp"
#include "craterkit/sph/solver/simulation.hpp"

using namespace craterkit::sph;
using namespace craterkit::impact;

namespace {

constexpr double g = 1.4e-4;  // m/s^2, Ryugu
constexpr double R = 3.0;     // m, domain radius L
constexpr double dx = 0.3;    // m

ImpactConfig target_config(double t_transition) {
  ImpactConfig config;
  config.simulation = SimulationConfig{};  // generic solver defaults: the test sets the impact ones it uses
  ImpactSetup setup;
  setup.domain_radius = R;
  setup.particle_spacing = dx;
  setup.transition_time = t_transition;
  config.impact = setup;
  config.simulation.solver.gravity = {0.0, 0.0, -g};
  config.simulation.run.end_time = 1e9;
  config.simulation.solver.time_step.velocity_change = 0.1;
  config.simulation.solver.time_step.energy_floor = 1e4;
  return config;
}

// The scenario without the projectile (material 1).
ProblemSetup target_only(const ImpactConfig& config) {
  ProblemSetup problem = build_impact_run(config).problem;
  Particles& p = problem.particles;
  std::vector<std::uint32_t> keep;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p.material[i] != 1) keep.push_back(static_cast<std::uint32_t>(i));
  p.for_each_field([&](std::string_view, auto& field) {
    auto kept = field;
    kept.resize(keep.size());
    for (std::size_t k = 0; k < keep.size(); ++k) kept[k] = field[keep[k]];
    field.swap(kept);
  });
  return problem;
}

struct RestFigures {
  double max_speed = 0.0;          // m/s, moving particles, over the run
  double max_surface_shift = 0.0;  // m, top-layer particles, over the run
  double crossing_time = 0.0;      // s
  std::uint64_t steps = 0;
};

// Runs `crossings` sound-crossing times R / c after `start` (c: the sound speed of the medium then, the
// largest particle sound speed, i.e. the longitudinal one with strength).
RestFigures run_at_rest(Simulation& sim, double start, double crossings) {
  const auto& p = sim.particles();
  std::vector<double> z0(p.size());
  std::vector<bool> top(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    z0[i] = p.z[i];
    top[i] = p.z[i] > -dx && (p.flags[i] & particle_fixed) == 0;
  }
  RestFigures f;
  while (sim.time() < start) sim.step(start);
  double c = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) c = std::max(c, p.sound_speed[i]);
  f.crossing_time = R / c;
  const double end = sim.time() + crossings * f.crossing_time;
  const std::uint64_t first = sim.step_count();
  while (sim.time() < end) {
    sim.step(end);
    for (std::size_t i = 0; i < p.size(); ++i) {
      if ((p.flags[i] & particle_fixed) != 0) continue;
      f.max_speed = std::max(f.max_speed, std::hypot(p.vx[i], p.vy[i], p.vz[i]));
    }
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!top[i]) continue;
    f.max_surface_shift = std::max(f.max_surface_shift, std::abs(p.z[i] - z0[i]));
  }
  f.steps = sim.step_count() - first;
  return f;
}

}  // namespace

TEST(LithostaticRest, TargetStaysAtRestBeforeTheTransition) {
  auto config = target_config(1e9);
  config.simulation.solver.neighbours.sort_interval =
      0;  // keep the particle order: surface shifts compare by index
  Simulation sim(config.simulation.solver, target_only(config));
  const auto f = run_at_rest(sim, 0.0, 20.0);
  const double free_fall = std::sqrt(g * R);
  std::printf(
      "before: %llu steps over 20 L/c = %.4g s: max speed %.3g m/s (%.3g sqrt(gL)), surface shift %.3g dx\n",
      static_cast<unsigned long long>(f.steps), 20 * f.crossing_time, f.max_speed, f.max_speed / free_fall,
      f.max_surface_shift / dx);
  EXPECT_LT(f.max_speed, 1e-3 * free_fall);
  EXPECT_LT(f.max_surface_shift, 0.05 * dx);
}

TEST(LithostaticRest, TargetStaysAtRestAfterTheTransition) {
  auto config = target_config(1e-4);
  config.simulation.solver.neighbours.sort_interval = 0;
  Simulation sim(config.simulation.solver, target_only(config));
  const auto f = run_at_rest(sim, 1e-4, 20.0);
  ASSERT_TRUE(sim.late_stage_active());
  const double free_fall = std::sqrt(g * R);
  std::printf(
      "after: %llu steps over 20 L/c = %.4g s: max speed %.3g m/s (%.3g sqrt(gL)), surface shift %.3g dx\n",
      static_cast<unsigned long long>(f.steps), 20 * f.crossing_time, f.max_speed, f.max_speed / free_fall,
      f.max_surface_shift / dx);
  EXPECT_LT(f.max_speed, 1e-3 * free_fall);
  EXPECT_LT(f.max_surface_shift, 0.05 * dx);
}
