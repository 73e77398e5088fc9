// The parts of `craterkit sweep` below the CLI: the TOML writer, the run claim (flock) and its inheritance by
// exactly the run's child, result.json and the tables assembled from run folders, the ETA, the Slurm script.
#include <gtest/gtest.h>
#include <sys/file.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "craterkit/common/child_process.hpp"
#include "craterkit/study/progress.hpp"
#include "craterkit/study/run_lock.hpp"
#include "craterkit/study/run_result.hpp"
#include "craterkit/study/slurm.hpp"
#include "craterkit/study/study_plan.hpp"
#include "craterkit/study/sweep_tables.hpp"
#include "craterkit/study/toml_document.hpp"
#include "study_test_helpers.hpp"

using namespace craterkit;
using namespace craterkit::study;
using namespace craterkit::study::test;

TEST(TomlDocument, EditsByDottedKeyAndWritesFloatsThatReadBackExactly) {
  TomlDocument doc = TomlDocument::parse(tiny_base(), "tiny");
  doc.set("impact.grading", "0.1");
  doc.set_number("new.table.value", 0.1 + 0.2);
  doc.set_text("problem.name", "run \"a\"");
  doc.set("output.snapshot_times", "[0, 1.5e-3]");
  EXPECT_TRUE(doc.erase("impact.t_transition"));
  EXPECT_FALSE(doc.erase("impact.t_transition"));
  EXPECT_EQ(doc.literal("impact.grading"), "0.1");
  EXPECT_EQ(doc.literal("run.gravity"), "[0.0, 0.0, -1.0]");
  EXPECT_EQ(doc.number("impact.projectile_mass"), 5450.0);
  EXPECT_THROW((void)doc.number("problem.setup"), InputError);
  EXPECT_THROW(doc.set("impact.grading.x", "1"), InputError);
  EXPECT_THROW(doc.set("impact.grading", "1 2"), InputError);
  const std::string text = doc.dump();
  const TomlDocument again = TomlDocument::parse(text, "again");
  EXPECT_EQ(again.dump(), text);
  EXPECT_EQ(again.number("new.table.value"), 0.1 + 0.2);
  EXPECT_EQ(again.text("problem.name"), "run \"a\"");
  EXPECT_FALSE(again.contains("impact.t_transition"));
  EXPECT_NE(text.find("[new.table]\nvalue = 0.30000000000000004\n"), std::string::npos) << text;
  EXPECT_NE(text.find("snapshot_times = [0, 0.0015]"), std::string::npos) << text;
  EXPECT_EQ(toml_float(2.0), "2.0");
  EXPECT_EQ(toml_float(1e-5), "1e-05");
  EXPECT_EQ(toml_float(1.4e-4), "0.00014");
  EXPECT_EQ(toml_float(-INFINITY), "-inf");
}

TEST(RunLock, OneHolderAtATime) {
  Scratch scratch;
  const auto file = scratch.path() / "lock";
  EXPECT_FALSE(is_locked(file));
  auto first = RunLock::try_acquire(file);
  ASSERT_TRUE(first);
  EXPECT_FALSE(RunLock::try_acquire(file));  // another open file description, as another process would have
  EXPECT_TRUE(is_locked(file));
  first.reset();
  EXPECT_FALSE(is_locked(file));
  EXPECT_TRUE(RunLock::try_acquire(file));
}

TEST(RunLock, TheRunsChildKeepsItsClaimAndNoOtherClaim) {
  Scratch scratch;
  auto mine = RunLock::try_acquire(scratch.path() / "mine");
  auto other = RunLock::try_acquire(scratch.path() / "other");
  ASSERT_TRUE(mine && other);
  ChildCommand sleep;
  sleep.program = "/bin/sleep";
  sleep.arguments = {"2"};
  sleep.stdout_file = scratch.path() / "out";
  sleep.stderr_file = scratch.path() / "err";
  sleep.inherited_fds = {mine->fd()};
  const pid_t pid = spawn_child(sleep);
  // The parent lets go of both, as a killed sweep would: the child still holds its run's claim, not the
  // other.
  mine.reset();
  other.reset();
  EXPECT_TRUE(is_locked(scratch.path() / "mine"));
  EXPECT_FALSE(is_locked(scratch.path() / "other"));
  EXPECT_FALSE(poll_child(pid).has_value());
  const ExitStatus status = wait_child(pid);
  EXPECT_TRUE(status.success()) << status.describe();
  EXPECT_FALSE(is_locked(scratch.path() / "mine"));
}

TEST(ChildProcess, ExitStatusAndOutput) {
  Scratch scratch;
  ChildCommand command;
  command.program = "/bin/sh";
  command.arguments = {"-c", "echo out; echo err >&2; exit 3"};
  command.stdout_file = scratch.path() / "stdout";
  command.stderr_file = scratch.path() / "stderr";
  scratch.write("stderr", "before\n");
  const ExitStatus status = wait_child(spawn_child(command));
  EXPECT_FALSE(status.success());
  EXPECT_EQ(status.code, 3);
  EXPECT_EQ(status.describe(), "exit status 3");
  EXPECT_EQ(read(scratch.path() / "stdout"), "out\n");
  EXPECT_EQ(read(scratch.path() / "stderr"), "before\nerr\n");  // appended
  command.arguments = {"-c", "kill -9 $$"};
  const ExitStatus killed = wait_child(spawn_child(command));
  EXPECT_TRUE(killed.signalled);
  EXPECT_EQ(killed.signal, 9);
}

namespace {

StudyPlan tiny_plan(const Scratch& scratch, const std::string& grid) {
  scratch.write("base.toml", tiny_base());
  const auto file = scratch.write("tiny-study.toml",
                                  "[study]\nname = \"tiny\"\ndescription = \"two runs\"\nbase = "
                                  "\"base.toml\"\n[sizing]\nenabled = false\n" +
                                      grid);
  return plan_study(load_study(file), scratch.path() / "out");
}

// What `craterkit simulate --json` and crater.json would hold, reduced to what the sweep reads.
std::string summary(bool ended, double transition_time) {
  return "{\"particles\": 536, \"steps\": 170, \"steps_this_run\": 85, \"time\": 0.3, \"wall_seconds\": 2.0, "
         "\"crater_growth_ended\": " +
         std::string(ended ? "true" : "false") +
         ", \"late_stage\": {\"transition_time\": " + std::to_string(transition_time) + "}}";
}
std::string crater(const std::string& radius) {
  return "{\"crater_radius\": " + radius +
         ", \"crater_radius_uncertainty\": 0.25, \"depth\": 1.0, "
         "\"settings\": {\"rho_initial\": 1300.0000000000002}}";
}

}  // namespace

TEST(SweepTables, ResultJsonAndTheTablesOfTheRunFolders) {
  Scratch scratch;
  const StudyPlan p = tiny_plan(scratch,
                                "[grid]\ncohesion = [0.0, 0.5]\nt_transition = [0.01]\n"
                                "[[runs]]\nA_low = 1e5\n");
  ASSERT_EQ(p.runs.size(), 3u);
  EXPECT_EQ(p.command, "craterkit sweep tiny-study.toml --out out");
  write_plan(p);
  const auto dir = [&](std::size_t k) { return run_directory(p.out, p.runs[k].name); };
  // Run 0 with a crater, run 1 without, run 2 failed.
  const std::string result0 =
      make_result_json(p, p.runs[0], summary(true, 0.01), crater("2.4554256566522383"), 3.0, 1);
  std::ofstream(dir(0) / "result.json") << result0;
  std::ofstream(dir(1) / "result.json")
      << make_result_json(p, p.runs[1], summary(false, 0.01), crater("null"), 3.0, 2);
  std::ofstream(dir(2) / "failed.json")
      << make_failure_json(p.runs[2].name, ExitStatus{false, 1, 0}, 1, 0.5, {"line 1", "boom"}, "");
  std::ofstream(dir(2) / "attempts.log") << "attempt 1\n";

  const auto r0 = read_result(dir(0));
  ASSERT_TRUE(r0);
  EXPECT_TRUE(r0->has_crater);
  EXPECT_EQ(r0->row.crater_radius, 2.4554256566522383);
  EXPECT_EQ(r0->row.target_density, 1300.0000000000002);  // the run record's (crater.json's rho_initial)
  EXPECT_EQ(r0->cost_seconds, 4.0);                       // 2 s for half the steps
  EXPECT_TRUE(r0->row.growth_ended);
  EXPECT_FALSE(read_result(dir(2)));
  std::ofstream(dir(2) / "result.json") << "{\"run\": ";  // incomplete: not a result
  EXPECT_FALSE(read_result(dir(2)));
  std::filesystem::remove(dir(2) / "result.json");

  char resolution[64];
  std::snprintf(resolution, sizeof(resolution), "%.17g", p.runs[0].resolution);
  const CollectReport report = collect(p.out, "craterkit 9.9 (git abc)");
  ASSERT_EQ(report.runs.size(), 3u);
  EXPECT_EQ(report.runs[0].status, RunStatus::done);
  EXPECT_EQ(report.runs[1].status, RunStatus::no_crater);
  EXPECT_EQ(report.runs[2].status, RunStatus::failed);
  EXPECT_EQ(report.rows, 1u);
  const std::string radii = read(p.out / "radii.csv");
  const std::string expected =
      "# craterkit sweep: study \"tiny\": two runs\n"
      "# craterkit 9.9 (git abc)\n"
      "# command: craterkit sweep tiny-study.toml --out out\n"
      "impactor_radius,impactor_density,velocity,target_density,gravity,strength,crater_radius,crater_radius_"
      "sigma,"
      "friction,porosity,resolution,t_transition,A_low,run,growth_ended\n"
      "1.0002798344485166,1300,50,1300.0000000000002,1,0,2.4554256566522383,0.25,0.55000000000000004,0.5," +
      std::string(resolution) + ",0.01,270000,cohesion-0_t_transition-0.01,true\n";
  EXPECT_EQ(radii, expected);
  const std::string runs = read(p.out / "runs.csv");
  EXPECT_NE(runs.find("cohesion-0.5_t_transition-0.01,no_crater,0,,,false,536,170,"), std::string::npos)
      << runs;
  EXPECT_NE(runs.find("A_low-1e+05,failed,1,"), std::string::npos) << runs;
  EXPECT_NE(runs.find("exit status 1"), std::string::npos) << runs;
  // The same folders give the same table.
  collect(p.out, "craterkit 9.9 (git abc)");
  EXPECT_EQ(read(p.out / "radii.csv"), expected);
  EXPECT_THROW(collect(scratch.path(), "x"), InputError);
}

TEST(SweepTables, TheDefaultTransitionTimeComesFromTheRun) {
  Scratch scratch;
  std::string base = tiny_base();
  scratch.write("base.toml", base);
  const StudyPlan p = tiny_plan(scratch, "[grid]\nt_transition = [0.0, 0.02]\n");
  write_plan(p);
  const auto result = make_result_json(p, p.runs[0], summary(false, 0.0333), crater("2.0"), 1.0, 1);
  std::ofstream(run_directory(p.out, p.runs[0].name) / "result.json") << result;
  const auto r = read_result(run_directory(p.out, p.runs[0].name));
  ASSERT_TRUE(r);
  EXPECT_EQ(r->row.extra, std::vector<std::string>{"0.033300000000000003"});
  EXPECT_EQ(p.runs[1].extra_cells, std::vector<std::string>{"0.02"});
}

TEST(Progress, EtaFromTheMeasuredCostPerParticle) {
  EXPECT_FALSE(estimate_seconds_left({}, {}, {std::nullopt, std::nullopt}, 1));
  // 100 s for 1000 particles: 0.1 s per particle. Left: a run of 2000 particles and one of unknown size (the
  // mean of the known: (1000 + 2000 + 3000) / 3); running: 3000 particles for 50 s. Two at once.
  const auto eta = estimate_seconds_left({{100.0, 1000.0}}, {{50.0, 3000.0}}, {2000.0, std::nullopt}, 2);
  ASSERT_TRUE(eta);
  EXPECT_DOUBLE_EQ(*eta, (200.0 + 200.0 + (300.0 - 50.0)) / 2.0);
  EXPECT_EQ(format_duration(3723.4), "1:02:03");
  EXPECT_EQ(format_duration(90000.0), "1 d 1:00:00");
  ProgressCounts counts{9, 3, 1, 2, 1, 3};
  EXPECT_EQ(progress_line(counts, std::nullopt),
            "sweep: 3/9 done, 1 failed, 2 running (1 elsewhere), 3 left, ETA unknown");
  EXPECT_EQ(progress_line(counts, 750.0),
            "sweep: 3/9 done, 1 failed, 2 running (1 elsewhere), 3 left, ETA 0:12:30");
}

TEST(Slurm, AJobArrayOfTheRuns) {
  Scratch scratch;
  const StudyPlan p = tiny_plan(scratch, "[grid]\ncohesion = [0.0, 0.5, 1.0]\n");
  const std::string script = slurm_script(p, {"/opt/craterkit/bin/craterkit", 4});
  EXPECT_EQ(script.rfind("#!/bin/bash\n", 0), 0u);
  EXPECT_NE(script.find("#SBATCH --array=0-2\n"), std::string::npos) << script;
  EXPECT_NE(script.find("#SBATCH --job-name=tiny\n"), std::string::npos);
  EXPECT_NE(script.find("#SBATCH --cpus-per-task=4\n"), std::string::npos);
  EXPECT_NE(script.find("#SBATCH --output=" + p.out.string() + "/logs/task-%a.out\n"), std::string::npos);
  EXPECT_NE(script.find("exec '/opt/craterkit/bin/craterkit' sweep '" + p.study.file.string() + "' --out '" +
                        p.out.string() +
                        "' --task \"$SLURM_ARRAY_TASK_ID\" --threads \"${SLURM_CPUS_PER_TASK:-4}\""),
            std::string::npos)
      << script;
  EXPECT_NE(script.find("sweep --collect " + p.out.string()), std::string::npos);
}
