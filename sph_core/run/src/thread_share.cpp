#include "craterkit/sph/run/thread_share.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace craterkit::sph {

ThreadShare::ThreadShare(ThreadShareOptions options)
    : options_(options),
      threads_(std::max(1, options.max_threads)),
      settled_threads_(threads_),
      retry_interval_(options.first_retry_seconds) {}

ThreadShare::Decision ThreadShare::observe(double now, double waiting_seconds) {
  Decision decision;
  if (options_.max_threads <= 1) return decision;
  if (!started_) {
    started_ = true;
    window_start_ = last_change_ = now;
    window_waiting_ = waiting_seconds;
    return decision;
  }
  const double wall = now - window_start_;
  if (wall < options_.window_seconds) return decision;
  const double waited = waiting_seconds - window_waiting_;
  window_start_ = now;
  window_waiting_ = waiting_seconds;
  // A thread that ended took its waiting time along with it: the window says nothing.
  if (waited < 0.0) return decision;
  const double waiting_fraction = waited / (wall * threads_);

  if (waiting_fraction > options_.waiting_limit && threads_ > 1) {
    int fewer = 0;
    if (trying_) {  // the full count still waits: back to the settled one, and try less often
      fewer = settled_threads_;
      retry_interval_ = std::min(2.0 * retry_interval_, options_.longest_retry_seconds);
    } else {
      // The share of the processors this run gets, in threads, is about threads x (1 - waiting fraction).
      const auto share = static_cast<int>(std::lround(threads_ * (1.0 - waiting_fraction)));
      fewer = std::clamp(share, 1, threads_ - 1);
      retry_interval_ = options_.first_retry_seconds;
      char text[200];
      std::snprintf(text, sizeof text,
                    "threads waited for a processor %.0f %% of the last %.1f s (other programs are running): "
                    "%d -> %d threads, %d tried again from time to time",
                    100.0 * waiting_fraction, wall, threads_, fewer, options_.max_threads);
      decision.note = text;
    }
    trying_ = false;
    threads_ = settled_threads_ = fewer;
    last_change_ = now;
    decision.threads = threads_;
    return decision;
  }
  if (trying_) {  // the full count ran a whole window without waiting: keep it
    trying_ = false;
    settled_threads_ = threads_;
    retry_interval_ = options_.first_retry_seconds;
    decision.note = "the processors are free again: back to " + std::to_string(threads_) + " threads";
    return decision;
  }
  if (threads_ < options_.max_threads && now - last_change_ >= retry_interval_) {
    trying_ = true;
    settled_threads_ = threads_;
    threads_ = options_.max_threads;
    last_change_ = now;
    decision.threads = threads_;
  }
  return decision;
}

std::optional<double> process_waiting_seconds() {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::directory_iterator tasks("/proc/self/task", ec);
  if (ec) return std::nullopt;
  double total_ns = 0.0;
  bool any = false;
  for (const auto& task : tasks) {
    // schedstat: time on a processor, time runnable but waiting for one (both ns), timeslices.
    std::ifstream in(task.path() / "schedstat");
    unsigned long long running_ns = 0, waiting_ns = 0;
    if (!(in >> running_ns >> waiting_ns)) continue;  // a thread that just ended, or no schedstat
    total_ns += static_cast<double>(waiting_ns);
    any = true;
  }
  if (!any) return std::nullopt;
  return total_ns * 1e-9;
}

}  // namespace craterkit::sph
