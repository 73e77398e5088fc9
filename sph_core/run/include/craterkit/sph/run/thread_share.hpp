#pragma once
// How many OpenMP threads a run uses while other programs compete for the processors.
//
// A block step is hundreds of short parallel loops, each ending at a barrier. When another program takes a
// processor, the operating system shares the remaining ones among this run's threads, and every barrier then
// waits for a thread that is not running: on 2 cores beside one busy program, 2 threads ran the SCI late
// stage 10-20 times slower than alone (bench/RESULTS.md), where one thread on the free core would be about 2
// times slower. The run therefore watches how long its threads wait for a processor (Linux schedstat: the
// time a thread was runnable but not running) and uses fewer threads while they wait; now and then it tries
// the full count again, and keeps it when the wait is gone. Results do not depend on the thread count
// (bitwise), so the change only moves the wall time.
#include <cstdint>
#include <optional>
#include <string>

namespace craterkit::sph {

struct ThreadShareOptions {
  int max_threads = 1;                   // the run's thread count (--threads): never more
  double window_seconds = 1.0;           // wall s over which the waiting is measured before a decision
  double waiting_limit = 0.15;           // fraction of a window a thread may wait for a processor, on average
  double first_retry_seconds = 30.0;     // wall s after a reduction before the full count is tried again
  double longest_retry_seconds = 240.0;  // the retry interval doubles after each failed try, up to this
};

// The decisions, from measurements passed in (testable without a busy machine). Not thread-safe: call from
// the thread that starts the parallel regions, between them.
class ThreadShare {
 public:
  explicit ThreadShare(ThreadShareOptions options);

  struct Decision {
    std::optional<int> threads;  // the thread count to use from now on, when it changes
    std::string note;  // for the run's log: a reduction, or the full count kept again ("" for the tries)
  };
  // One measurement at wall time `now` (s, any origin, non-decreasing): `waiting_seconds` is the total time
  // the process's threads have waited for a processor since any fixed origin.
  Decision observe(double now, double waiting_seconds);
  // True when observe() at `now` would measure (a window has passed, or nothing was observed yet): the
  // caller reads the waiting time only then.
  [[nodiscard]] bool due(double now) const {
    return options_.max_threads > 1 && (!started_ || now - window_start_ >= options_.window_seconds);
  }

  [[nodiscard]] int threads() const { return threads_; }
  // True while the full count is being tried again after a reduction (not yet kept).
  [[nodiscard]] bool trying() const { return trying_; }

 private:
  ThreadShareOptions options_;
  int threads_;
  bool started_ = false;
  bool trying_ = false;
  int settled_threads_;      // the count before the current try
  double window_start_ = 0;  // wall s
  double window_waiting_ = 0;
  double last_change_ = 0;  // wall s
  double retry_interval_;
};

// The total time (s) the threads of this process have waited for a processor (the second field of
// /proc/self/task/*/schedstat, summed); nothing where the system does not say (not Linux, no schedstat).
std::optional<double> process_waiting_seconds();

}  // namespace craterkit::sph
