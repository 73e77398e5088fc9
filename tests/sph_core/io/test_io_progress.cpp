// Phase timers and the progress line (with a scripted clock, so the numbers are exact).
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "craterkit/sph/solver/phase_timers.hpp"
#include "craterkit/sph/run/progress.hpp"

namespace sph = craterkit::sph;

TEST(IoPhaseTimers, AccumulatesPerPhaseInFirstUseOrder) {
  sph::PhaseTimers timers;
  timers.add("rates", 2.0);
  timers.add("neighbours", 1.0);
  timers.add("rates", 4.0);
  EXPECT_EQ(timers.seconds("rates"), 6.0);
  EXPECT_EQ(timers.calls("rates"), 2u);
  EXPECT_EQ(timers.seconds("output"), 0.0);
  EXPECT_EQ(timers.total_seconds(), 7.0);
  const auto pairs = timers.seconds_by_phase();
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0].first, "rates");
  EXPECT_EQ(pairs[1].first, "neighbours");

  // rates: 6 s of 7 = 85.7 %, 2 calls of 3000 ms.
  const std::string table = timers.table();
  EXPECT_NE(table.find("rates             6.000    85.7          2     3000.000"), std::string::npos)
      << table;
  EXPECT_NE(table.find("total             7.000   100.0"), std::string::npos) << table;
  timers.reset();
  EXPECT_TRUE(timers.phases().empty());
}

TEST(IoPhaseTimers, ScopeMeasuresWallTime) {
  sph::PhaseTimers timers;
  {
    auto scope = timers.measure("output");
    std::this_thread::sleep_for(std::chrono::milliseconds(30));
  }
  EXPECT_GE(timers.seconds("output"), 0.029);
  EXPECT_LT(timers.seconds("output"), 5.0);
  EXPECT_EQ(timers.calls("output"), 1u);
}

TEST(IoProgress, FormatsTheLine) {
  sph::ProgressSample s;
  s.time = 0.0123;
  s.end_time = 0.05;
  s.step = 123;
  s.dt = 1.23e-4;
  s.particle_updates_per_second = 341000;
  s.seconds_left = 3723.4;  // 1 h 2 min 3 s
  EXPECT_EQ(
      sph::format_progress(s),
      "t 1.2300e-02 / 5.0000e-02 s  step 123  dt 1.230e-04 s  3.410e+05 particle-updates/s  left 1:02:03");
  s.end_time = 0;
  s.seconds_left = -1;
  EXPECT_EQ(sph::format_progress(s),
            "t 1.2300e-02 s  step 123  dt 1.230e-04 s  3.410e+05 particle-updates/s  left ?");
}

namespace {
std::string contents(std::FILE* file) {
  std::fflush(file);
  std::rewind(file);
  std::string text;
  for (int c; (c = std::fgetc(file)) != EOF;) text += static_cast<char>(c);
  return text;
}
}  // namespace

TEST(IoProgress, PrintsEveryIntervalWithRatesOverTheInterval) {
  std::FILE* log = std::tmpfile();
  ASSERT_NE(log, nullptr);
  double wall = 100;
  sph::ProgressOptions options;
  options.end_time = 0.5;
  options.log_interval_seconds = 10;
  sph::Progress progress(options, log, [&] { return wall; });
  EXPECT_FALSE(progress.is_terminal());

  progress.update(0.0, 0, 1e-3, 0);  // starts the clock (1000 particles: 1000 updates per step)
  wall = 105;
  progress.update(0.05, 10, 1e-3, 10000);  // too early: nothing
  EXPECT_EQ(contents(log), "");
  wall = 110;
  progress.update(0.1, 20, 1e-3, 20000);
  // 1000 particles x 20 steps in 10 s = 2000 /s; 0.1 s simulated in 10 s, 0.4 s left -> 40 s.
  EXPECT_EQ(
      contents(log),
      "t 1.0000e-01 / 5.0000e-01 s  step 20  dt 1.000e-03 s  2.000e+03 particle-updates/s  left 0:00:40\n");
  std::fseek(log, 0, SEEK_END);
  wall = 130;
  progress.finish(0.5, 100, 1e-3, 100000);  // whole run: 1e5 updates in 30 s
  EXPECT_NE(contents(log).find("step 100  dt 1.000e-03 s  3.333e+03 particle-updates/s  left 0:00:00\n"),
            std::string::npos);
  std::fclose(log);
}

// Before the end of a first stage (the late-stage switch) the time left is to that stage's end, and the
// line says so: the pace of the shock stage says nothing about the late stage, whose own pace is measured
// from the switch on.
TEST(IoProgress, EstimatesToTheEndOfTheFirstStageBeforeIt) {
  std::FILE* log = std::tmpfile();
  ASSERT_NE(log, nullptr);
  double wall = 0;
  sph::ProgressOptions options;
  options.end_time = 500.0;
  options.stage_end_time = 0.1;
  options.log_interval_seconds = 10;
  sph::Progress progress(options, log, [&] { return wall; });
  progress.update(0.0, 0, 1e-4, 0);
  wall = 20;
  progress.update(0.02, 200, 1e-4, 200000);
  // 0.02 s in 20 s, 0.08 s to the switch -> 80 s.
  EXPECT_EQ(
      contents(log),
      "t 2.0000e-02 / 5.0000e+02 s  step 200  dt 1.000e-04 s  1.000e+04 particle-updates/s  left 0:01:20"
      " to t = 1.0000e-01 s\n");
  std::fseek(log, 0, SEEK_END);
  const long before = std::ftell(log);
  // The switch lands at t = 0.1 s after 200 s of wall time (a slow end of the first stage): no line, the
  // late stage's pace is measured from here.
  wall = 200;
  progress.update(0.1, 300, 0.1, 300000);
  EXPECT_EQ(contents(log).substr(static_cast<std::size_t>(before)), "");
  wall = 220;
  progress.update(100.1, 1300, 0.1, 1300000);
  // 100 s simulated in 20 s, 399.9 s to the end -> 79.98 s; 1e6 updates in 20 s. Measured over the interval
  // from t = 0.02 s (wall 20 s) it would say 400 s.
  const std::string last = contents(log).substr(static_cast<std::size_t>(before));
  EXPECT_EQ(
      last,
      "t 1.0010e+02 / 5.0000e+02 s  step 1300  dt 1.000e-01 s  5.000e+04 particle-updates/s  left 0:01:20\n");
  std::fclose(log);
}

TEST(IoProgress, SilencedPrintsNothing) {
  std::FILE* log = std::tmpfile();
  ASSERT_NE(log, nullptr);
  double wall = 0;
  sph::ProgressOptions options;
  options.enabled = false;
  sph::Progress progress(options, log, [&] { return wall; });
  for (int step = 0; step < 5; ++step) {
    wall += 100;
    progress.update(step, static_cast<std::uint64_t>(step), 1, 10u * static_cast<std::uint64_t>(step));
  }
  progress.finish(5, 5, 1, 50);
  EXPECT_EQ(contents(log), "");
  std::fclose(log);
}
