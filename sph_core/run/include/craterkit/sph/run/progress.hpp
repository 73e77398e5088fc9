#pragma once
// The progress line of a running simulation: simulated time, step, dt, particle updates per second
// and the estimated wall time left. On a terminal it is redrawn in place (carriage return, at most
// a few times per second); otherwise (log file, pipe) one full line is printed every
// `log_interval_seconds`. Rates are measured over the interval since the previous line.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>

namespace craterkit::sph {

struct ProgressOptions {
  bool enabled = true;  // false: print nothing
  double end_time = 0;  // s, simulated end time (for the time left; 0: unknown)
  // s, end of a first stage whose pace says nothing about the rest (the late-stage switch of an impact: its
  // time step is hundreds of times longer after it). Before it the time left is estimated to it and the
  // line says so; after it the pace is measured from the end of the stage on; 0: no such stage.
  double stage_end_time = 0;
  double redraw_seconds = 0.25;      // terminal: minimum wall time between redraws
  double log_interval_seconds = 10;  // not a terminal: wall time between lines
};

// One measurement, as shown on the line.
struct ProgressSample {
  double time = 0;      // simulated time, s
  double end_time = 0;  // s (0: unknown)
  std::uint64_t step = 0;
  double dt = 0;                           // s
  double particle_updates_per_second = 0;  // particle updates / wall s over the last interval
  double seconds_left = -1;                // wall s; negative: unknown
  double left_until = 0;                   // s: the simulated time seconds_left reaches, if not end_time
};

// "t 1.2340e-02 / 5.0000e-02 s  step 123  dt 1.23e-04 s  3.41e+05 particle-updates/s  left 0:01:23", with
// " to t = 1.0000e-01 s" appended when the estimate is to the end of a first stage (ProgressOptions).
std::string format_progress(const ProgressSample& sample);

class Progress {
 public:
  // stream: where to print (stderr by default); whether it is a terminal is detected with isatty.
  // clock: wall time in seconds (steady clock by default; tests pass their own).
  explicit Progress(ProgressOptions options, std::FILE* stream = stderr, std::function<double()> clock = {});

  // Call once per completed step with the state after the step and the number of particle updates so far
  // (Simulation::particle_updates(): particles x steps with a global step). Prints when due.
  void update(double time, std::uint64_t step, double dt, std::uint64_t particle_updates);
  // Prints the final state with the rate averaged over the whole run (on a terminal: ends the line).
  // Call once at the end of the run.
  void finish(double time, std::uint64_t step, double dt, std::uint64_t particle_updates);

  [[nodiscard]] bool is_terminal() const { return terminal_; }

 private:
  ProgressSample sample(double time, std::uint64_t step, double dt, std::uint64_t updates, double now,
                        double since_wall, double since_time, std::uint64_t since_updates) const;
  void print(const ProgressSample& s, bool final_line);

  ProgressOptions options_;
  std::FILE* stream_;
  std::function<double()> clock_;
  bool terminal_ = false;
  bool started_ = false;
  double last_print_wall_ = 0;
  double last_print_time_ = 0;
  std::uint64_t last_print_updates_ = 0;
  double start_wall_ = 0;  // first update(): the origin of the whole-run rate
  double start_time_ = 0;
  std::uint64_t start_updates_ = 0;
};

}  // namespace craterkit::sph
