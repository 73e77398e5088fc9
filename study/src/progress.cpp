#include "craterkit/study/progress.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

namespace craterkit::study {

std::optional<double> estimate_seconds_left(const std::vector<CostSample>& finished,
                                            const std::vector<RunningRun>& running,
                                            const std::vector<std::optional<double>>& left, int jobs) {
  double seconds = 0.0, particles = 0.0;
  double known = 0.0, known_count = 0.0;
  for (const auto& s : finished) {
    if (!(s.seconds > 0.0 && s.particles > 0.0)) continue;
    seconds += s.seconds;
    particles += s.particles;
    known += s.particles;
    known_count += 1.0;
  }
  if (!(particles > 0.0)) return std::nullopt;
  const double per_particle = seconds / particles;
  for (const auto& r : running) {
    if (r.particles) {
      known += *r.particles;
      known_count += 1.0;
    }
  }
  for (const auto& n : left) {
    if (n) {
      known += *n;
      known_count += 1.0;
    }
  }
  const double mean_particles = known / known_count;
  double work = 0.0;
  for (const auto& n : left) work += per_particle * n.value_or(mean_particles);
  for (const auto& r : running)
    work += std::max(0.0, per_particle * r.particles.value_or(mean_particles) - r.elapsed);
  return work / static_cast<double>(std::max(1, jobs));
}

std::string format_duration(double seconds) {
  const long long total = std::llround(std::max(0.0, seconds));
  const long long days = total / 86400;
  const long long h = (total % 86400) / 3600, m = (total % 3600) / 60, s = total % 60;
  const std::string clock = fmt::format("{}:{:02}:{:02}", h, m, s);
  return days > 0 ? fmt::format("{} d {}", days, clock) : clock;
}

std::string progress_line(const ProgressCounts& c, std::optional<double> seconds_left) {
  std::string running = fmt::format("{} running", c.running);
  if (c.elsewhere > 0) running += fmt::format(" ({} elsewhere)", c.elsewhere);
  const std::string eta = c.running + c.left == 0 ? ""
                          : seconds_left          ? ", ETA " + format_duration(*seconds_left)
                                                  : ", ETA unknown";
  return fmt::format("sweep: {}/{} done, {} failed, {}, {} left{}", c.done, c.total, c.failed, running,
                     c.left, eta);
}

}  // namespace craterkit::study
