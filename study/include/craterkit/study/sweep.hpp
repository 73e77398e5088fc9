#pragma once
// Running a study (docs/sweep.md): every run of the plan not yet finished is claimed (run_lock.hpp) and run
// as a child process (run_attempt.hpp), `jobs` at a time; finished runs are skipped, interrupted ones
// resumed, failed ones skipped unless retry_failed; runs claimed by another process are waited for. Progress
// lines go to `log`. At the end the tables are collected (sweep_tables.hpp).
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "craterkit/study/progress.hpp"
#include "craterkit/study/run_attempt.hpp"
#include "craterkit/study/study_plan.hpp"
#include "craterkit/study/sweep_tables.hpp"

namespace craterkit::study {

struct SweepOptions {
  ChildSettings child;
  int jobs = 1;
  bool retry_failed = false;
  std::string producer;            // the tables' header line: "craterkit <version> (git <commit>)"
  std::ostream* log = nullptr;     // progress lines; null: none
  double poll_seconds = 0.2;       // how often the children are checked
  double elsewhere_seconds = 2.0;  // how often a run claimed by another process is tried again
};

struct SweepReport {
  ProgressCounts counts;  // at the end
  CollectReport tables;
  std::size_t started = 0;  // children this process started
};

// The processors this process may use (its CPU affinity), at least 1.
int available_cores();
// --threads default: available_cores() / jobs, at least 1.
int default_threads(int jobs);

// Runs the study (write_plan must have been called) until every run is finished or failed.
SweepReport run_sweep(const StudyPlan& plan, const SweepOptions& options);

// Runs exactly plan.runs[index] (a Slurm array task): nothing when it is finished; waits while another
// process runs it; skips it when it failed before unless retry_failed.
RunRecord run_task(const StudyPlan& plan, std::size_t index, const SweepOptions& options);

}  // namespace craterkit::study
