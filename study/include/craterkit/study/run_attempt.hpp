#pragma once
// One attempt at a run: its child `craterkit simulate DIR/runs/<name>/config.toml --out DIR/runs/<name>
// --threads T --resume --json --quiet`, started holding the run's claim (run_lock.hpp), and what is written
// when it ends: result.json (atomically, only after the child succeeded) or failed.json. The child's stdout
// (its summary) goes to simulate.out.json, its stderr is appended to simulate.log after a line naming the
// attempt; attempts.log gets one line per attempt before the child starts.
#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>

#include "craterkit/common/child_process.hpp"
#include "craterkit/study/run_lock.hpp"
#include "craterkit/study/run_result.hpp"
#include "craterkit/study/study_plan.hpp"

namespace craterkit::study {

struct ChildSettings {
  std::filesystem::path program;  // the craterkit executable
  int threads = 1;                // --threads of each child
};

struct Attempt {
  std::size_t run = 0;  // index in the plan
  RunLock lock;
  pid_t pid = 0;
  int number = 0;  // 1 for a run's first attempt
  std::chrono::steady_clock::time_point started;
  std::uintmax_t log_offset = 0;  // where this attempt's stderr starts in simulate.log
};

// Starts the child of plan.runs[run], which inherits `lock`.
Attempt start_attempt(const StudyPlan& plan, std::size_t run, RunLock lock, const ChildSettings& child);

// Writes result.json or failed.json for an attempt whose child ended with `status`; the record's status is
// done, no_crater or failed, or interrupted when the child was stopped by SIGINT, SIGTERM or SIGHUP (then
// nothing is written: the next sweep resumes it). The claim is released when `attempt` is destroyed.
RunRecord finish_attempt(const StudyPlan& plan, const Attempt& attempt, const ExitStatus& status);

// The particle count a running child has reported on stderr (its set-up line), when it has.
std::optional<double> reported_particles(const std::filesystem::path& log, std::uintmax_t offset);

}  // namespace craterkit::study
