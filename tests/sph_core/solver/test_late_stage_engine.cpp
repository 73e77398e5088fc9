// The late-stage transition in the engine (docs/physics.md section 3): at t_transition every material
// switches to the low-sound-speed law, the step that would pass it ends on it, the time step grows with the
// lower sound speed, the switch and the Mach numbers are recorded in the snapshot attributes, and a run
// resumed from a checkpoint written before or after the switch ends bit for bit where an uninterrupted
// run ends.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "craterkit/sph/io/checkpoint.hpp"
#include "craterkit/sph/run/standard_problem_config.hpp"
#include "craterkit/sph/solver/simulation.hpp"
#include "sph_core/engine_test_helpers.hpp"

using namespace craterkit::sph;
namespace fs = std::filesystem;

namespace {

constexpr double t_transition = 1.0e-6;  // s
constexpr double A_low = 1.0e9;          // Pa

// Planar aluminium-on-basalt impact (fluid Tillotson materials), 1 mm lattice: ~100 steps to 4 us.
StandardProblemConfig plates(std::uint64_t max_steps) {
  StandardProblemConfig config;
  PlateImpactSetup setup;
  setup.particle_spacing = 1e-3;
  setup.cross_section_particles = 6;
  config.problem = setup;
  config.simulation.run.end_time = 2e-6;
  config.simulation.run.max_steps = max_steps;
  config.simulation.solver.neighbours.sort_interval = 7;
  config.late_stage.transition_time = t_transition;
  config.late_stage.A_low = A_low;
  config.simulation.output.checkpoint_interval_steps = 5;
  config.simulation.output.checkpoint_interval_seconds = 0;
  return config;
}

fs::path scratch(const std::string& name) {
  const auto dir = fs::temp_directory_path() / ("craterkit_late_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(LateStageEngine, SwitchLandsOnTransitionTimeAndTheTimeStepGrows) {
  const auto config = plates(0);
  Simulation sim(config.simulation.solver, build_standard_problem(config));
  double dt_before = 0.0;
  while (!sim.late_stage_active()) {
    ASSERT_LT(sim.time(), t_transition) << "the switch was missed";
    dt_before = sim.next_time_step();
    sim.step(config.simulation.run.end_time);
  }
  EXPECT_EQ(sim.time(), t_transition);  // the step was shortened to end on it
  for (const auto& m : sim.materials()) {
    ASSERT_TRUE(std::holds_alternative<LowSoundSpeed>(m.eos)) << m.name;
    EXPECT_EQ(std::get<LowSoundSpeed>(m.eos).A, A_low);
  }
  // Every particle's sound speed is now sqrt(A_low / rho0) of its material.
  const auto& p = sim.particles();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto& law = std::get<LowSoundSpeed>(sim.materials()[p.material[i]].eos);
    ASSERT_NEAR(p.sound_speed[i], std::sqrt(A_low / law.reference_density), 1e-9 * p.sound_speed[i]);
  }
  // The Mach number at the switch, recomputed independently.
  double mach = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i)
    mach = std::max(mach, std::hypot(p.vx[i], p.vy[i], p.vz[i]) / p.sound_speed[i]);
  EXPECT_DOUBLE_EQ(sim.mach_at_transition(), mach);
  EXPECT_GT(mach, 1.0);  // 1 km/s particle speeds against c = 0.6 km/s: a deliberately hard switch
  // The Courant step grows by about c_before / c_after (basalt: 3.1 km/s -> 0.61 km/s, i.e. ~5x; the
  // shocked state and the viscous signal speed make it less): at least twice the last shock-stage step.
  EXPECT_GT(sim.next_time_step(), 2.0 * dt_before);
  const double mach_at_switch = sim.mach_at_transition();
  for (int k = 0; k < 20 && sim.time() < config.simulation.run.end_time; ++k)
    sim.step(config.simulation.run.end_time);
  EXPECT_GE(sim.late_stage_max_mach(), mach_at_switch);
  const auto a = sim.state();
  EXPECT_TRUE(a.late_stage_active);
  EXPECT_EQ(a.transition_time, t_transition);
  EXPECT_EQ(a.A_low, A_low);
  EXPECT_EQ(a.mach_at_transition, mach_at_switch);
  EXPECT_EQ(a.late_stage_max_mach, sim.late_stage_max_mach());
}

// The block steps' neighbour rule: one level between neighbours in the shock stage, two from the first block
// after the switch (docs/physics.md section 1.12), also in a run resumed from a state written after it.
TEST(LateStageEngine, BlockStepsAllowTwoLevelsBetweenNeighboursAfterTheSwitch) {
  auto config = plates(0);
  config.simulation.solver.time_step.block_levels = 4;
  const ProblemSetup problem = build_standard_problem(config);
  Simulation sim(config.simulation.solver, problem);
  while (!sim.late_stage_active()) {
    ASSERT_LT(sim.time(), t_transition) << "the switch was missed";
    sim.step(config.simulation.run.end_time);
    EXPECT_EQ(sim.block_schedule().neighbour_levels(), block_neighbour_levels);
  }
  EXPECT_EQ(block_neighbour_levels, 1);
  sim.step(config.simulation.run.end_time);
  EXPECT_EQ(sim.block_schedule().neighbour_levels(), 2);
  Simulation resumed(config.simulation.solver, problem, sim.particles(), sim.state());
  resumed.step(config.simulation.run.end_time);
  EXPECT_EQ(resumed.block_schedule().neighbour_levels(), 2);
}

// What the switch carries (simulation.hpp): without gravity there is no lithostatic part, so every
// particle's pressure is the shock-stage pressure scaled by sqrt(A_low/A) of its material (the elastic
// energy P^2/(2K) of the wave kept), unless the matrix strain cap of 0.1 holds it. The shock-stage state
// just before the switch comes from the same run without a transition, stepped to t_transition.
TEST(LateStageEngine, PressureOfTheWavesIsScaledToKeepItsEnergy) {
  const auto config = plates(0);
  auto no_switch = config;
  no_switch.late_stage.transition_time = 0.0;
  no_switch.late_stage.A_low = 0.0;
  Simulation switched(config.simulation.solver, build_standard_problem(config));
  Simulation reference(no_switch.simulation.solver, build_standard_problem(no_switch));
  while (!switched.late_stage_active()) {
    switched.step(config.simulation.run.end_time);
    reference.step(t_transition);
    ASSERT_EQ(switched.time(), reference.time());
  }
  const auto& before = reference.particles();
  const auto& after = switched.particles();
  std::size_t scaled = 0, capped = 0;
  for (std::size_t i = 0; i < after.size(); ++i) {
    const auto A = solid_reference(reference.materials()[before.material[i]].eos)->bulk_modulus;
    const double expected = before.pressure[i] * std::sqrt(A_low / A);
    if (std::abs(expected) > late_stage_max_reference_strain * A_low) {
      ++capped;
      ASSERT_NEAR(std::abs(after.pressure[i]), late_stage_max_reference_strain * A_low, 1e-6 * A_low) << i;
      continue;
    }
    ASSERT_NEAR(after.pressure[i], expected, 1e-9 * A_low) << i;
    if (std::abs(expected) > 1e-3 * A_low) ++scaled;
  }
  std::printf("%zu particles: %zu with a wave pressure scaled, %zu at the strain cap\n", after.size(), scaled,
              capped);
  EXPECT_GT(scaled, after.size() / 10);  // the check is not vacuous
}

TEST(LateStageEngine, ResumedRunsEqualTheUninterruptedRunAcrossTheSwitch) {
  RunOptions options;
  options.progress = false;
  options.log = false;
  // The step of the switch, S (checkpoints are every 5 steps; a checkpoint forces a neighbour rebuild, so
  // the "killed" runs must stop on that grid to follow the same sequence).
  std::uint64_t switch_step = 0;
  {
    Simulation sim(plates(0).simulation.solver, build_standard_problem(plates(0)));
    while (!sim.late_stage_active()) sim.step(1.0);
    switch_step = sim.step_count();
  }
  ASSERT_GT(switch_step, 10u);
  const std::uint64_t before = 5 * (switch_step / 10), after = 5 * ((switch_step + 7) / 5);
  const std::uint64_t total = after + 10;
  const auto straight = scratch("straight");
  options.output_directory = straight;
  const auto full = run_standard_problem(plates(total), options);
  ASSERT_TRUE(full.late_stage);
  // Checkpoints before the switch and after it resume to the same end.
  for (const std::uint64_t checkpoint_step : {before, after}) {
    const auto partial = scratch("partial");
    options.output_directory = partial;
    options.resume = false;
    run_standard_problem(plates(checkpoint_step), options);
    RunAttributes a;
    read_checkpoint(partial / "checkpoint.h5", &a);
    ASSERT_EQ(a.step, checkpoint_step);
    EXPECT_EQ(a.numbers.count("late_stage_transition_time"), checkpoint_step == after ? 1u : 0u);
    options.resume = true;
    const auto summary = run_standard_problem(plates(total), options);
    EXPECT_TRUE(summary.resumed);
    EXPECT_TRUE(summary.late_stage);
    EXPECT_EQ(summary.mach_at_transition, full.mach_at_transition);
    EXPECT_EQ(summary.late_stage_max_mach, full.late_stage_max_mach);
    RunAttributes x, y;
    const Particles one = read_checkpoint(straight / "checkpoint.h5", &x);
    const Particles two = read_checkpoint(partial / "checkpoint.h5", &y);
    EXPECT_EQ(x.time, y.time);
    EXPECT_EQ(x.numbers.at("next_time_step"), y.numbers.at("next_time_step"));
    engine_test::expect_identical_particles(one, two);
    EXPECT_EQ(read_text(straight / "conservation.csv"), read_text(partial / "conservation.csv"));
    fs::remove_all(partial);
  }
  fs::remove_all(straight);
}
