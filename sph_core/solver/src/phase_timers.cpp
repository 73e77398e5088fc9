#include "craterkit/sph/solver/phase_timers.hpp"

#include <algorithm>
#include <cstdio>

namespace craterkit::sph {

PhaseTimers::Scope::Scope(PhaseTimers& timers, std::string_view phase)
    : timers_(&timers), index_(timers.index_of(phase)), start_(std::chrono::steady_clock::now()) {}

void PhaseTimers::Scope::stop() {
  if (timers_ == nullptr) return;
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start_;
  auto& phase = timers_->phases_[index_];
  phase.seconds += elapsed.count();
  phase.calls += 1;
  timers_ = nullptr;
}

std::size_t PhaseTimers::index_of(std::string_view phase) {
  for (std::size_t k = 0; k < phases_.size(); ++k) {
    if (phases_[k].name == phase) return k;
  }
  phases_.push_back({std::string(phase), 0.0, 0});
  return phases_.size() - 1;
}

void PhaseTimers::add(std::string_view phase, double seconds) {
  auto& entry = phases_[index_of(phase)];
  entry.seconds += seconds;
  entry.calls += 1;
}

double PhaseTimers::seconds(std::string_view phase) const {
  for (const auto& entry : phases_) {
    if (entry.name == phase) return entry.seconds;
  }
  return 0;
}

std::uint64_t PhaseTimers::calls(std::string_view phase) const {
  for (const auto& entry : phases_) {
    if (entry.name == phase) return entry.calls;
  }
  return 0;
}

double PhaseTimers::total_seconds() const {
  double total = 0;
  for (const auto& entry : phases_) total += entry.seconds;
  return total;
}

std::vector<std::pair<std::string, double>> PhaseTimers::seconds_by_phase() const {
  std::vector<std::pair<std::string, double>> pairs;
  pairs.reserve(phases_.size());
  for (const auto& entry : phases_) pairs.emplace_back(entry.name, entry.seconds);
  return pairs;
}

std::string PhaseTimers::table() const {
  std::size_t width = 5;  // "total"
  for (const auto& entry : phases_) width = std::max(width, entry.name.size());
  const double total = total_seconds();
  std::string out;
  char line[256];
  std::snprintf(line, sizeof line, "%-*s %12s %7s %10s %12s\n", static_cast<int>(width), "phase", "seconds",
                "%", "calls", "ms/call");
  out += line;
  for (const auto& entry : phases_) {
    const double percent = total > 0 ? 100.0 * entry.seconds / total : 0.0;
    const double per_call = entry.calls > 0 ? 1e3 * entry.seconds / static_cast<double>(entry.calls) : 0.0;
    std::snprintf(line, sizeof line, "%-*s %12.3f %7.1f %10llu %12.3f\n", static_cast<int>(width),
                  entry.name.c_str(), entry.seconds, percent, static_cast<unsigned long long>(entry.calls),
                  per_call);
    out += line;
  }
  std::snprintf(line, sizeof line, "%-*s %12.3f %7.1f\n", static_cast<int>(width), "total", total,
                total > 0 ? 100.0 : 0.0);
  out += line;
  return out;
}

}  // namespace craterkit::sph
