#include "craterkit/impact/crater_growth.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace craterkit::impact {

using namespace sph;

CraterGrowthCriteria growth_criteria(const CraterGrowthParameters& p) {
  CraterGrowthCriteria criteria;
  criteria.radius_tolerance = p.radius_tolerance;
  criteria.kinetic_energy_fraction = p.kinetic_energy_fraction;
  criteria.window_fraction = p.window_fraction;
  return criteria;
}

bool crater_growth_ended(std::span<const CraterGrowthSample> samples, const CraterGrowthCriteria& c) {
  if (samples.empty()) return false;
  const auto& last = samples.back();
  if (!(last.time > 0.0) || !(last.radius > 0.0) || !std::isfinite(last.radius)) return false;
  double peak = 0.0;
  for (const auto& s : samples) peak = std::max(peak, s.kinetic_energy);
  if (!(peak > 0.0)) return false;
  const double start = (1.0 - c.window_fraction) * last.time;
  std::size_t in_window = 0;
  double smallest = last.radius, largest = last.radius;
  for (const auto& s : samples) {
    if (s.time < start) continue;
    ++in_window;
    if (!std::isfinite(s.radius)) return false;
    smallest = std::min(smallest, s.radius);
    largest = std::max(largest, s.radius);
    if (s.kinetic_energy > c.kinetic_energy_fraction * peak) return false;
  }
  // The whole band of the window, not each sample against the last one: a crater whose measured radius
  // jumped inwards by ~1 % and then grew again would otherwise look settled while it still grows (the SCI
  // run of docs/crater_measurement.md, "End of crater growth").
  return in_window >= c.min_window_samples && largest - smallest <= c.radius_tolerance * last.radius;
}

std::optional<std::size_t> first_sample_of_ended_growth(std::span<const CraterGrowthSample> samples,
                                                        const CraterGrowthCriteria& criteria) {
  for (std::size_t k = 0; k < samples.size(); ++k) {
    if (crater_growth_ended(samples.first(k + 1), criteria)) return k;
  }
  return std::nullopt;
}

double moving_kinetic_energy(const Particles& p) {
  // Summed over fixed blocks of particles, then the blocks in order: the same bits for any thread count. The
  // value feeds the termination test, and a run may change its thread count on the way
  // (run/thread_share.hpp).
  constexpr std::size_t block = 4096;
  const std::size_t n = p.size();
  const std::size_t blocks = (n + block - 1) / block;
  std::vector<double> block_sums(blocks, 0.0);
#pragma omp parallel for schedule(static)
  for (std::int64_t bb = 0; bb < static_cast<std::int64_t>(blocks); ++bb) {
    const auto b = static_cast<std::size_t>(bb);
    double sum = 0.0;
    for (std::size_t i = b * block; i < std::min(n, (b + 1) * block); ++i) {
      if ((p.flags[i] & (particle_fixed | particle_ejected)) != 0) continue;
      sum += 0.5 * p.mass[i] * (p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
    }
    block_sums[b] = sum;
  }
  double sum = 0.0;
  for (const double s : block_sums) sum += s;
  return sum;
}

}  // namespace craterkit::impact
