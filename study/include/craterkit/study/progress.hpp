#pragma once
// The progress of a sweep (docs/sweep.md, "Progress"): counts of runs and the time left, estimated from the
// measured cost of the finished runs: the mean wall time per particle of the finished runs times the
// particles still to simulate, divided by the runs going at once. Particle counts of runs not yet finished
// that are not known (a run reports its count when its set-up is built) are taken as the mean of the known
// ones (the sizing rule keeps them alike).
#include <optional>
#include <string>
#include <vector>

namespace craterkit::study {

struct ProgressCounts {
  std::size_t total = 0, done = 0, failed = 0, running = 0, elsewhere = 0, left = 0;
};

// A finished run's cost: its wall seconds for all its steps, and its particle count.
struct CostSample {
  double seconds = 0.0;
  double particles = 0.0;
};

// A run going in this process: wall seconds so far and its particles when known.
struct RunningRun {
  double elapsed = 0.0;
  std::optional<double> particles;
};

// Seconds left, or nullopt before any run has finished (or without a usable sample). `left` holds the
// particle counts (when known) of the runs not started, including those running elsewhere, whose progress
// is unknown.
std::optional<double> estimate_seconds_left(const std::vector<CostSample>& finished,
                                            const std::vector<RunningRun>& running,
                                            const std::vector<std::optional<double>>& left, int jobs);

// "1:02:03" (h:mm:ss), or "2 d 3:04:05".
std::string format_duration(double seconds);

// "sweep: 3/9 done, 1 failed, 2 running (1 elsewhere), 3 left, ETA 0:12:30" (or "ETA unknown").
std::string progress_line(const ProgressCounts& counts, std::optional<double> seconds_left);

}  // namespace craterkit::study
