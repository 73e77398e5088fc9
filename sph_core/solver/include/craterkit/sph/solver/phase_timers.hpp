#pragma once
// Wall-time accumulation per phase of a run (neighbours, rates, integration, output, ...), so that
// every run can print where its time went and regressions show. Not thread-safe: time phases from the
// serial code around the OpenMP regions, not from inside them.
//
//   PhaseTimers timers;
//   { auto scope = timers.measure("neighbours"); build_neighbours(...); }
//   std::cerr << timers.table();
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace craterkit::sph {

class PhaseTimers {
 public:
  struct Phase {
    std::string name;
    double seconds = 0;
    std::uint64_t calls = 0;
  };

  // Adds the wall time from construction to destruction (or stop()) to one phase.
  class Scope {
   public:
    Scope(PhaseTimers& timers, std::string_view phase);
    ~Scope() { stop(); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;
    void stop();

   private:
    PhaseTimers* timers_;
    std::size_t index_;
    std::chrono::steady_clock::time_point start_;
  };

  [[nodiscard]] Scope measure(std::string_view phase) { return Scope(*this, phase); }
  void add(std::string_view phase, double seconds);  // one call of `seconds`

  [[nodiscard]] double seconds(std::string_view phase) const;  // 0 for a phase never timed
  [[nodiscard]] std::uint64_t calls(std::string_view phase) const;
  [[nodiscard]] double total_seconds() const;
  // Phases in the order they were first timed.
  [[nodiscard]] const std::vector<Phase>& phases() const { return phases_; }
  // (name, seconds) pairs, e.g. for a JSON object {"neighbours": 1.2, ...}.
  [[nodiscard]] std::vector<std::pair<std::string, double>> seconds_by_phase() const;
  // A text table: phase, seconds, percent of the total, calls, milliseconds per call; last row total.
  [[nodiscard]] std::string table() const;
  void reset() { phases_.clear(); }

 private:
  std::size_t index_of(std::string_view phase);  // adds the phase if new
  std::vector<Phase> phases_;
};

}  // namespace craterkit::sph
