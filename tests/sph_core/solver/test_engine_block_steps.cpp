// Block time steps in the engine (block_time_steps.hpp): the Sedov blast (a hot centre whose steps are
// far shorter than those of the cold gas around it) against the similarity solution and against the
// same run with one global step; a run killed at a checkpoint resumes bit-for-bit; the result does not
// depend on the thread count.
#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "craterkit/sph/io/checkpoint.hpp"
#include "craterkit/sph/run/standard_problem_config.hpp"
#include "sph_core/engine_sedov_common.hpp"
#include "sph_core/engine_test_helpers.hpp"

using namespace craterkit::sph;
namespace fs = std::filesystem;

TEST(BlockTimeSteps, SedovBlastMatchesTheSimilaritySolutionWithFewerUpdates) {
  // Continuity density (block steps need it), 30^3: the global-step run is +0.56 % (docs/validation.md).
  const auto global = engine_test::run_sedov(30, DensityMethod::continuity, 0);
  const auto block = engine_test::run_sedov(30, DensityMethod::continuity, 6);
  std::printf(
      "Sedov 30^3, continuity: global r_s %+.2f %% dE %.2e, %llu updates; block (6 levels) r_s %+.2f %% dE "
      "%.2e peak %.3f (global %.3f), %llu updates\n",
      100.0 * (global.shock_radius / global.analytic_radius - 1.0), global.energy_error,
      static_cast<unsigned long long>(global.particle_updates),
      100.0 * (block.shock_radius / block.analytic_radius - 1.0), block.energy_error, block.peak_density,
      global.peak_density, static_cast<unsigned long long>(block.particle_updates));
  EXPECT_NEAR(block.shock_radius / block.analytic_radius, 1.0, 0.03);
  EXPECT_NEAR(block.shock_radius / global.shock_radius, 1.0, 0.005);
  EXPECT_NEAR(block.peak_density / global.peak_density, 1.0, 0.02);
  // Pair forces of particles on different levels are not simultaneous: energy to the integration error.
  EXPECT_LT(block.energy_error, 1e-3);
  // The cold gas takes long steps: at most a third of the global run's particle updates.
  EXPECT_LT(3 * block.particle_updates, global.particle_updates);
}

namespace {

StandardProblemConfig small_sod(std::uint64_t max_steps) {
  StandardProblemConfig config;
  SodSetup setup;
  setup.left_particles_per_length = 40;
  setup.cross_section = 12.0 / 40;
  config.problem = setup;
  config.simulation.run.end_time = 0.2;
  config.simulation.run.max_steps = max_steps;
  config.simulation.solver.viscosity.viscosity_switch = ViscositySwitch::morris_monaghan;
  config.simulation.solver.neighbours.sort_interval = 3;
  config.simulation.solver.neighbours.search.skin = 0.1;
  config.simulation.solver.time_step.block_levels = 4;
  config.simulation.output.checkpoint_interval_steps = 4;
  config.simulation.output.checkpoint_interval_seconds = 0;
  return config;
}

fs::path scratch(const std::string& name) {
  const auto dir = fs::temp_directory_path() / ("craterkit_block_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir;
}

}  // namespace

TEST(BlockTimeSteps, ResumedRunEqualsUninterruptedRunBitwise) {
  RunOptions options;
  options.progress = false;
  const auto straight = scratch("straight");
  options.output_directory = straight;
  const auto whole = run_standard_problem(small_sod(14), options);
  ASSERT_EQ(whole.steps, 14u);
  // Several levels in use (the left gas is hotter), or the test would show nothing: more updates than one
  // per particle and block, fewer than if every particle were on the finest of the 4 levels.
  EXPECT_GT(whole.particle_updates, whole.particles * whole.steps);
  EXPECT_LT(whole.particle_updates, whole.particles * whole.steps * 16);

  // Killed after its step-8 checkpoint: the state of a run that stopped there.
  const auto resumed = scratch("resumed");
  options.output_directory = resumed;
  run_standard_problem(small_sod(8), options);
  options.resume = true;
  const auto rest = run_standard_problem(small_sod(14), options);
  EXPECT_TRUE(rest.resumed);
  EXPECT_EQ(rest.steps, 14u);

  RunAttributes a, b;
  const Particles one = read_checkpoint(straight / "checkpoint.h5", &a);
  const Particles two = read_checkpoint(resumed / "checkpoint.h5", &b);
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.numbers.at("next_time_step"), b.numbers.at("next_time_step"));
  engine_test::expect_identical_particles(one, two);
  for (const auto& dir : {straight, resumed}) fs::remove_all(dir);
}

TEST(BlockTimeSteps, ResultIndependentOfThreadCount) {
  const auto config = small_sod(10);
  omp_set_num_threads(1);
  auto one = engine_test::run_to(config, 0.2);
  omp_set_num_threads(2);
  auto two = engine_test::run_to(config, 0.2);
  EXPECT_EQ(one.particle_updates(), two.particle_updates());
  engine_test::expect_identical_particles(one.particles(), two.particles());
}

// Simulation::memory_use (bytes_per_particle by part): each part counts at least what it must hold for this
// run (block steps with kept lists, a fluid with the viscosity switch), and the fields no more than they hold.
TEST(BlockTimeSteps, MemoryUseCountsEachPart) {
  const auto config = small_sod(10);
  Simulation sim(config.simulation.solver, build_standard_problem(config));
  for (int block = 0; block < 3; ++block) sim.step(0.2);
  const MemoryUse use = sim.memory_use();

  std::size_t field_bytes = 0;  // one value of every field
  sim.particles().for_each_field([&](std::string_view, const auto& field) {
    field_bytes += sizeof(typename std::decay_t<decltype(field)>::value_type);
  });
  EXPECT_GE(use.particle_fields, double(field_bytes));
  EXPECT_LT(use.particle_fields, 1.25 * double(field_bytes));
  // Kept lists: an offset and an end per particle and at least the interacting pairs' entries.
  EXPECT_GE(use.neighbour_lists, 16.0 + 4.0 * sim.mean_neighbours());
  EXPECT_GT(use.neighbour_search, 0.0);
  EXPECT_GE(use.integrator, 6.0 * sizeof(double));  // a, drho/dt, du/dt, dalpha/dt of the step's start
  EXPECT_GE(use.rate_pass, double(sizeof(double) + sizeof(std::uint32_t)));     // signal time, count
  EXPECT_GE(use.schedule, 3.0 + 2.0 * sizeof(std::uint64_t) + sizeof(double));  // BlockSchedule's arrays
  EXPECT_EQ(use.distributed, 0.0);
}
