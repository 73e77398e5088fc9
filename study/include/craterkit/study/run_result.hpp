#pragma once
// What a run's folder says about it (docs/sweep.md, "Run folders"):
//   result.json   written atomically once the run's child succeeded: its radii.csv row, the crater, the
//                 simulate summary; present = finished
//   failed.json   the child's exit status and the end of its stderr; present (and no result) = failed
//   attempts.log  one line per child started, with its time, host and process ids
//   lock          the claim (run_lock.hpp); held = running
//   checkpoint.h5 without a result: interrupted, resumed by the next sweep
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "craterkit/common/child_process.hpp"
#include "craterkit/study/study_plan.hpp"

namespace craterkit::study {

// A row of radii.csv (sweep_tables.hpp).
struct RadiiRow {
  double impactor_radius = 0.0, impactor_density = 0.0, velocity = 0.0, target_density = 0.0, gravity = 0.0,
         strength = 0.0, crater_radius = 0.0, crater_radius_sigma = 0.0;
  double friction = 0.0, porosity = 0.0, resolution = 0.0;
  std::vector<std::string> extra;  // the study's extra columns (sweep.json), as text
  std::string run;
  bool growth_ended = false;
};

enum class RunStatus { pending, interrupted, running, done, no_crater, failed };
std::string to_string(RunStatus status);

// A finished run (result.json).
struct RunResult {
  RadiiRow row;  // crater_radius NaN when no crater was found
  bool has_crater = false;
  double crater_depth = 0.0;  // m (NaN without a crater)
  long long particles = 0, steps = 0;
  double simulated_time = 0.0;  // s
  double wall_seconds = 0.0;    // of the child that finished it
  double cost_seconds = 0.0;    // wall seconds for all its steps (scaled from a resumed child; 0 if unknown)
  int attempts = 0;
};

// result.json of a run whose child succeeded, from the child's --json summary and crater.json.
// std::runtime_error when either is not what `craterkit simulate` writes.
std::string make_result_json(const StudyPlan& plan, const PlannedRun& run, const std::string& summary_text,
                             const std::string& crater_text, double wall_seconds, int attempts);
// The result of a run folder; nullopt when absent or incomplete.
std::optional<RunResult> read_result(const std::filesystem::path& run_dir);

struct RunFailure {
  std::string description;  // "exit status 1", "killed by signal 11 (Segmentation fault)"
  int exit_status = -1;     // -1 when killed by a signal
  int attempt = 0;
  std::vector<std::string> stderr_tail;
};

std::string make_failure_json(const std::string& run, const ExitStatus& status, int attempt,
                              double wall_seconds, const std::vector<std::string>& stderr_tail,
                              const std::string& message);
std::optional<RunFailure> read_failure(const std::filesystem::path& run_dir);

int count_attempts(const std::filesystem::path& run_dir);

// The state of a run folder as runs.csv reports it.
struct RunRecord {
  std::string name;
  RunStatus status = RunStatus::pending;
  std::optional<RunResult> result;
  std::optional<RunFailure> failure;
  int attempts = 0;
};
RunRecord inspect_run(const std::filesystem::path& out, const std::string& name);

}  // namespace craterkit::study
