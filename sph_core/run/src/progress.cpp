#include "craterkit/sph/run/progress.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <string>

namespace craterkit::sph {
namespace {

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string hours_minutes_seconds(double seconds) {
  if (!(seconds >= 0) || !std::isfinite(seconds)) return "?";
  const auto total = static_cast<unsigned long long>(std::llround(seconds));
  char text[64];
  std::snprintf(text, sizeof text, "%llu:%02llu:%02llu", total / 3600, (total / 60) % 60, total % 60);
  return text;
}

}  // namespace

std::string format_progress(const ProgressSample& s) {
  char line[256];
  std::string time = [&] {
    char text[64];
    if (s.end_time > 0) {
      std::snprintf(text, sizeof text, "t %.4e / %.4e s", s.time, s.end_time);
    } else {
      std::snprintf(text, sizeof text, "t %.4e s", s.time);
    }
    return std::string(text);
  }();
  std::snprintf(line, sizeof line, "%s  step %llu  dt %.3e s  %.3e particle-updates/s  left %s", time.c_str(),
                static_cast<unsigned long long>(s.step), s.dt, s.particle_updates_per_second,
                hours_minutes_seconds(s.seconds_left).c_str());
  std::string text = line;
  if (s.left_until > 0 && s.left_until != s.end_time && s.seconds_left >= 0) {
    char until[64];
    std::snprintf(until, sizeof until, " to t = %.4e s", s.left_until);
    text += until;
  }
  return text;
}

Progress::Progress(ProgressOptions options, std::FILE* stream, std::function<double()> clock)
    : options_(options),
      stream_(stream),
      clock_(clock ? std::move(clock) : std::function<double()>(steady_seconds)) {
  terminal_ = stream_ != nullptr && ::isatty(::fileno(stream_)) == 1;
}

ProgressSample Progress::sample(double time, std::uint64_t step, double dt, std::uint64_t updates, double now,
                                double since_wall, double since_time, std::uint64_t since_updates) const {
  ProgressSample s;
  s.time = time;
  s.end_time = options_.end_time;
  s.step = step;
  s.dt = dt;
  const double wall = now - since_wall;
  s.particle_updates_per_second = wall > 0 ? static_cast<double>(updates - since_updates) / wall : 0;
  // Time left from the rate of simulated time over the last interval.
  const double simulated = time - since_time;
  s.left_until = options_.stage_end_time > time ? options_.stage_end_time : options_.end_time;
  if (s.left_until > 0 && wall > 0 && simulated > 0) {
    s.seconds_left = std::max(0.0, s.left_until - time) * wall / simulated;
  }
  return s;
}

void Progress::update(double time, std::uint64_t step, double dt, std::uint64_t particle_updates) {
  if (!options_.enabled || stream_ == nullptr) return;
  const double now = clock_();
  if (!started_) {  // the first call starts the clock: no rate yet
    started_ = true;
    start_wall_ = now;
    start_time_ = time;
    start_updates_ = particle_updates;
    last_print_wall_ = now;
    last_print_time_ = time;
    last_print_updates_ = particle_updates;
    return;
  }
  if (options_.stage_end_time > 0 && last_print_time_ < options_.stage_end_time &&
      time >= options_.stage_end_time) {
    // The first stage just ended: the next stage's pace is measured from here, not over an interval that
    // holds the slow end of the first one (which made a run 9 minutes from its end say "37 h left").
    last_print_wall_ = now;
    last_print_time_ = time;
    last_print_updates_ = particle_updates;
    return;
  }
  const double interval = terminal_ ? options_.redraw_seconds : options_.log_interval_seconds;
  if (now - last_print_wall_ < interval) return;
  print(
      sample(time, step, dt, particle_updates, now, last_print_wall_, last_print_time_, last_print_updates_),
      false);
  last_print_wall_ = now;
  last_print_time_ = time;
  last_print_updates_ = particle_updates;
}

void Progress::finish(double time, std::uint64_t step, double dt, std::uint64_t particle_updates) {
  if (!options_.enabled || stream_ == nullptr) return;
  const double now = clock_();
  ProgressSample s =
      started_ ? sample(time, step, dt, particle_updates, now, start_wall_, start_time_, start_updates_)
               : ProgressSample{time, options_.end_time, step, dt, 0, -1};
  s.seconds_left = 0;
  print(s, true);
}

void Progress::print(const ProgressSample& s, bool final_line) {
  const std::string line = format_progress(s);
  if (terminal_) {
    // Redraw in place: carriage return, the line, erase what is left of a longer previous line.
    std::fprintf(stream_, "\r%s\033[K%s", line.c_str(), final_line ? "\n" : "");
  } else {
    std::fprintf(stream_, "%s\n", line.c_str());
  }
  std::fflush(stream_);
}

}  // namespace craterkit::sph
