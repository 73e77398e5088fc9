// A graded-resolution target (docs/impact_setup.md "Graded resolution") in lithostatic equilibrium stays at
// rest in the engine, with the criteria of test_lithostatic_rest.cpp for the uniform lattice: over 20
// sound-crossing times L / c before the late-stage switch the largest speed stays below 1e-3 of the
// free-fall speed sqrt(g L), and the top layer moves less than 0.05 local spacings (each particle's own,
// V^(1/3)). The target is the impact set-up's graded hemisphere (make_impact through the engine's
// scenario) without its projectile: a core of spacing dx0, the junction, graded shells and the outer
// spacing, for the steepest allowed grading and for the default one; and, as for the lattice, after the
// late-stage switch.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <variant>
#include <vector>

#include "craterkit/impact/impact_run.hpp"
#include "craterkit/sph/solver/simulation.hpp"

using namespace craterkit::sph;
using namespace craterkit::impact;

namespace {

constexpr double g = 1.4e-4;  // m/s^2, Ryugu
constexpr double R = 2.0;     // m, domain radius L (small: the fine particles set the time step)

ImpactConfig target_config(double dx0, double dx_max, double grading, double inner_radius,
                           double t_transition = 1e9) {
  ImpactConfig config;
  config.simulation = SimulationConfig{};  // generic solver defaults: the test sets the impact ones it uses
  ImpactSetup setup;
  setup.domain_radius = R;
  setup.particle_spacing = dx_max;
  setup.inner_spacing = dx0;
  setup.grading = grading;
  setup.inner_radius = inner_radius;
  setup.transition_time = t_transition;  // default: no late-stage switch within the run
  config.impact = setup;
  config.simulation.solver.gravity = {0.0, 0.0, -g};
  config.simulation.run.end_time = 1e9;
  config.simulation.solver.time_step.velocity_change = 0.1;
  config.simulation.solver.time_step.energy_floor = 1e4;
  config.simulation.solver.neighbours.sort_interval =
      0;  // keep the particle order: surface shifts compare by index
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
  double max_speed = 0.0;  // m/s, moving particles, over the run
  double max_shift = 0.0;  // top-layer particles' vertical shift in their own spacings, over the run
  double crossing_time = 0.0;
  std::size_t particles = 0, top = 0;
  std::uint64_t steps = 0;
  bool late_stage = false;
};

// Runs `crossings` sound-crossing times R / c after `start` (c: the largest particle sound speed then, the
// longitudinal one with strength).
RestFigures run_at_rest(const ImpactConfig& config, double start, double crossings) {
  Simulation sim(config.simulation.solver, target_only(config));
  const auto& p = sim.particles();
  RestFigures f;
  f.particles = p.size();
  std::vector<double> z0(p.size()), spacing(p.size());
  std::vector<bool> top(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    z0[i] = p.z[i];
    spacing[i] = std::cbrt(p.mass[i] / p.density[i]);  // the cell's edge: dx0 in the core, dx_k outside
    top[i] = p.z[i] > -spacing[i] && (p.flags[i] & particle_fixed) == 0;
    f.top += top[i] ? 1 : 0;
  }
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
      if (top[i]) f.max_shift = std::max(f.max_shift, std::abs(p.z[i] - z0[i]) / spacing[i]);
    }
  }
  f.steps = sim.step_count() - first;
  f.late_stage = sim.late_stage_active();
  return f;
}

void expect_at_rest(const char* when, const ImpactConfig& config, double start) {
  const RestFigures f = run_at_rest(config, start, 20.0);
  const auto& s = config.impact;
  const double free_fall = std::sqrt(g * R);
  std::printf(
      "%s: graded dx0 = %.3g, dx_max = %.3g, s = %.2f: %zu particles (%zu top), %llu steps over 20 L/c = "
      "%.4g s: max speed %.3g m/s (%.3g sqrt(gL)), top-layer shift %.3g local spacings\n",
      when, s.inner_spacing, s.particle_spacing, s.grading, f.particles, f.top,
      static_cast<unsigned long long>(f.steps), 20 * f.crossing_time, f.max_speed, f.max_speed / free_fall,
      f.max_shift);
  EXPECT_EQ(f.late_stage, start > 0.0);
  EXPECT_LT(f.max_speed, 1e-3 * free_fall);
  EXPECT_LT(f.max_shift, 0.05);
}

}  // namespace

// Core r < 0.4 m at 0.1 m, graded shells to 0.2 m at r = 1.0 m, outer spacing to 2 m (2,360 particles,
// ~2,400 steps).
TEST(GradedRest, SteepestGradingStaysAtRestBeforeTheTransition) {
  expect_at_rest("before", target_config(0.1, 0.2, 0.2, 0.4), 0.0);
}

// Core r < 0.5 m at 0.125 m, graded shells growing by 6 % per spacing to 0.2 m at r = 1.8 m.
TEST(GradedRest, DefaultGradingStaysAtRestBeforeTheTransition) {
  expect_at_rest("before", target_config(0.125, 0.2, 0.06, 0.5), 0.0);
}

// The same after the low-sound-speed switch (c ~ 3.6 m/s), where the target spends most of a run. The
// largest speed (~4e-4 sqrt(gL), against ~1e-4 on the uniform lattice) is that of a polar-ring particle
// next to the fixed shell, and decays after the switch.
TEST(GradedRest, SteepestGradingStaysAtRestAfterTheTransition) {
  expect_at_rest("after", target_config(0.1, 0.2, 0.2, 0.4, 1e-4), 1e-4);
}
