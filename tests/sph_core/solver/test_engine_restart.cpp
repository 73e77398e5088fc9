// The driver: a run killed after a checkpoint and resumed ends bit-for-bit where an uninterrupted
// run ends (same thread count), including the conservation log; results do not depend on the
// thread count; momentum is conserved to round-off over a whole run; the JSON summary figures.
#include <gtest/gtest.h>
#include <omp.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "craterkit/common/version.hpp"
#include "craterkit/sph/io/checkpoint.hpp"
#include "craterkit/sph/run/standard_problem_config.hpp"
#include "sph_core/engine_test_helpers.hpp"

using namespace craterkit::sph;
namespace fs = std::filesystem;

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
  config.simulation.solver.neighbours.sort_interval = 7;
  config.simulation.output.checkpoint_interval_steps = 10;
  config.simulation.output.checkpoint_interval_seconds = 0;
  return config;
}

fs::path scratch(const std::string& name) {
  const auto dir =
      fs::temp_directory_path() / ("craterkit_engine_" + name + "_" + std::to_string(::getpid()));
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

TEST(Restart, ResumedRunEqualsUninterruptedRunBitwise) {
  RunOptions options;
  options.progress = false;
  const auto straight = scratch("straight");
  options.output_directory = straight;
  run_standard_problem(small_sod(45), options);

  // The "killed" run stops after 23 steps; its last checkpoint is from step 20 (the final one written
  // at step 23 is removed, as if the process had died before writing it).
  const auto resumed = scratch("resumed");
  options.output_directory = resumed;
  run_standard_problem(small_sod(23), options);
  {
    RunAttributes a;
    read_checkpoint(resumed / "checkpoint.h5", &a);
    ASSERT_EQ(a.step, 23u);
  }
  // Replace the final checkpoint by the step-20 state of an identical run.
  const auto partial = scratch("partial");
  options.output_directory = partial;
  run_standard_problem(small_sod(20), options);
  fs::copy_file(partial / "checkpoint.h5", resumed / "checkpoint.h5", fs::copy_options::overwrite_existing);

  options.output_directory = resumed;
  options.resume = true;
  const auto summary = run_standard_problem(small_sod(45), options);
  EXPECT_TRUE(summary.resumed);
  EXPECT_EQ(summary.steps, 45u);
  EXPECT_EQ(summary.steps_this_run, 25u);

  RunAttributes a, b;
  const Particles one = read_checkpoint(straight / "checkpoint.h5", &a);
  const Particles two = read_checkpoint(resumed / "checkpoint.h5", &b);
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(a.numbers.at("next_time_step"), b.numbers.at("next_time_step"));
  engine_test::expect_identical_particles(one, two);
  EXPECT_EQ(read_text(straight / "conservation.csv"), read_text(resumed / "conservation.csv"));
  for (const auto& dir : {straight, resumed, partial}) fs::remove_all(dir);
}

TEST(Restart, ResultIndependentOfThreadCount) {
  const auto config = small_sod(30);
  omp_set_num_threads(1);
  auto one = engine_test::run_to(config, 0.2);
  omp_set_num_threads(2);
  auto two = engine_test::run_to(config, 0.2);
  // Gather-form pair loops and a deterministic neighbour search: identical, not merely close.
  engine_test::expect_identical_particles(one.particles(), two.particles());
}

// Lists kept from step to step with a skin (the default) and lists rebuilt at every step hold the same pairs
// within the support: the runs differ only in the order of their pair sums, so by round-off.
TEST(Restart, KeptListsChangeTheRunOnlyByRoundOff) {
  auto kept_config = small_sod(40);
  ASSERT_GT(kept_config.simulation.solver.neighbours.search.skin, 0.0);
  auto rebuilt_config = kept_config;
  rebuilt_config.simulation.solver.neighbours.search.skin = 0.0;
  const auto kept = engine_test::run_to(kept_config, 0.2);
  const auto rebuilt = engine_test::run_to(rebuilt_config, 0.2);
  EXPECT_EQ(kept.step_count(), rebuilt.step_count());
  const Particles& a = kept.particles();
  const Particles& b = rebuilt.particles();
  ASSERT_EQ(a.size(), b.size());
  double largest_speed = 0.0, largest_difference = 0.0, largest_density_difference = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a.id[i], b.id[i]);  // the same curve sorts at the same steps
    largest_speed = std::max(largest_speed, std::abs(a.vx[i]));
    largest_difference = std::max(largest_difference, std::abs(a.vx[i] - b.vx[i]));
    largest_density_difference =
        std::max(largest_density_difference, std::abs(a.density[i] - b.density[i]) / b.density[i]);
  }
  EXPECT_GT(largest_difference, 0.0) << "the sums are taken in another order";
  EXPECT_LT(largest_difference, 1e-12 * largest_speed);
  EXPECT_LT(largest_density_difference, 1e-12);
}

TEST(Restart, SummaryReportsTheIssueFigures) {
  RunOptions options;
  options.progress = false;
  const auto dir = scratch("summary");
  options.output_directory = dir;
  auto config = small_sod(0);
  config.simulation.run.end_time = 0.02;
  config.simulation.output.snapshot_times = {0.0, 0.01};
  options.configuration = "# the configuration\nsetup = \"sod\"\n";
  const auto s = run_standard_problem(config, options);
  EXPECT_GT(s.particles, 0u);
  EXPECT_GT(s.steps, 0u);
  EXPECT_DOUBLE_EQ(s.time, 0.02);
  EXPECT_GT(s.wall_seconds, 0.0);
  EXPECT_NEAR(s.particle_updates_per_second, s.particles * static_cast<double>(s.steps) / s.wall_seconds,
              1e-9 * s.particle_updates_per_second);
  EXPECT_GT(s.mean_neighbours, 40.0);
  EXPECT_LT(s.mean_neighbours, 80.0);
  EXPECT_LT(s.relative_momentum_error, 1e-12);
  EXPECT_TRUE(s.momentum_conserved);  // no gravity, no fixed particles, no mirror planes
  EXPECT_LT(s.relative_energy_error, 1e-3);
  EXPECT_EQ(s.snapshots.size(), 3u);  // t = 0, 0.01 and the final state
  EXPECT_TRUE(fs::exists(dir / "snapshots.xdmf"));
  EXPECT_TRUE(fs::exists(dir / "conservation.csv"));
  // Every snapshot and the checkpoint record the code version and the configuration text.
  RunAttributes snapshot, checkpoint;
  read_snapshot(s.snapshots.front(), &snapshot);
  read_checkpoint(dir / "checkpoint.h5", &checkpoint);
  for (const RunAttributes* a : {&snapshot, &checkpoint}) {
    EXPECT_EQ(a->texts.at("craterkit_version"), craterkit::version());
    EXPECT_EQ(a->texts.at("configuration"), options.configuration);
  }
  fs::remove_all(dir);
}
