#include "craterkit/impact/crater_growth.hpp"

#include <algorithm>
#include <cmath>

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
  const auto n = static_cast<std::int64_t>(p.size());
  double sum = 0.0;
  // Fixed static schedule and a reduction: the value may differ in the last bits with the thread count;
  // it only feeds the termination test, never the state.
#pragma omp parallel for schedule(static) reduction(+ : sum)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if ((p.flags[i] & (particle_fixed | particle_ejected)) != 0) continue;
    sum += 0.5 * p.mass[i] * (p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
  }
  return sum;
}

}  // namespace craterkit::impact
