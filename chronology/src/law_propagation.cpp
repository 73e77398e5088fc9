// The scaling law's uncertainty through the chronology (see law_propagation.hpp).
#include "craterkit/chronology/law_propagation.hpp"

#include <algorithm>
#include <cstddef>

#include "craterkit/chronology/scaled_production.hpp"
#include "craterkit/common/input_error.hpp"

namespace craterkit::chronology {
namespace {

constexpr std::size_t kStrata = 1000;  // quantiles taken of each draw's age density

// The quantiles of a density tabulated on an increasing grid at increasing probabilities, in one sweep of
// its trapezoidal CDF (density_quantile in one pass for many probabilities).
void append_quantiles(const std::vector<double>& grid, const std::vector<double>& density,
                      const std::vector<double>& probabilities, std::vector<double>& out) {
  std::vector<double> cdf(grid.size(), 0.0);
  for (std::size_t i = 1; i < grid.size(); ++i)
    cdf[i] = cdf[i - 1] + 0.5 * (density[i] + density[i - 1]) * (grid[i] - grid[i - 1]);
  const double total = cdf.back();
  std::size_t k = 1;
  for (double q : probabilities) {
    const double target = q * total;
    while (k < cdf.size() - 1 && cdf[k] < target) ++k;
    const double step = cdf[k] - cdf[k - 1];
    const double f = step > 0.0 ? std::clamp((target - cdf[k - 1]) / step, 0.0, 1.0) : 0.0;
    out.push_back(grid[k - 1] + f * (grid[k] - grid[k - 1]));
  }
}

// Quantile q of values (sorted), linear between order statistics.
double sorted_quantile(const std::vector<double>& sorted, double q) {
  const double position = q * static_cast<double>(sorted.size() - 1);
  const auto below = static_cast<std::size_t>(position);
  const std::size_t above = std::min(below + 1, sorted.size() - 1);
  return sorted[below] + (position - static_cast<double>(below)) * (sorted[above] - sorted[below]);
}

}  // namespace

RateSpread rate_spread(const ProductionSetup& setup, const std::vector<scaling::ScalingLaw>& laws,
                       const scaling::Target& target, const scaling::Target& reference,
                       double impactor_density, double rim_diameter) {
  if (laws.empty()) throw InputError("rate spread: no draws of the scaling law");
  const double speed = mean_speed(setup.speeds);
  const double radius = apparent_radius_from_rim_diameter(rim_diameter, setup.diameter);
  std::vector<double> impactor, rate, relative;
  for (const auto& law : laws) {
    const auto a_of_r = scaled_impactor_radius(law, target, impactor_density);
    const double r = crater_production_rate(setup, a_of_r, rim_diameter);
    const double r_reference =
        crater_production_rate(setup, scaled_impactor_radius(law, reference, impactor_density), rim_diameter);
    impactor.push_back(a_of_r(radius, speed));
    rate.push_back(r);
    relative.push_back(r / r_reference);
  }
  return {scaling::percentiles(impactor), scaling::percentiles(rate), scaling::percentiles(relative)};
}

AgeSpread model_age_spread(const CraterCounts& counts, const ProductionSetup& setup,
                           const std::vector<scaling::ScalingLaw>& laws, const scaling::Target& target,
                           double impactor_density, const AgeFitOptions& options) {
  if (laws.empty()) throw InputError("age spread: no draws of the scaling law");
  AgeFitOptions draw_options = options;
  draw_options.cumulative_fit = false;
  std::vector<double> probabilities(kStrata);
  for (std::size_t j = 0; j < kStrata; ++j)
    probabilities[j] = (static_cast<double>(j) + 0.5) / static_cast<double>(kStrata);
  std::vector<double> medians;
  std::vector<double> pooled;
  pooled.reserve(laws.size() * kStrata);
  for (const auto& law : laws) {
    const auto production = production_function(setup, scaled_impactor_radius(law, target, impactor_density));
    const AgeEstimate age = fit_model_age(counts, production, draw_options);
    medians.push_back(age.median);
    append_quantiles(age.age_grid, age.density, probabilities, pooled);
  }
  std::sort(pooled.begin(), pooled.end());
  AgeSpread out;
  out.median = scaling::percentiles(medians);
  out.total_median = sorted_quantile(pooled, 0.5);
  out.total_sigma1_low = sorted_quantile(pooled, 0.158655);
  out.total_sigma1_high = sorted_quantile(pooled, 0.841345);
  out.total_sigma2_low = sorted_quantile(pooled, 0.0227501);
  out.total_sigma2_high = sorted_quantile(pooled, 0.9772499);
  return out;
}

}  // namespace craterkit::chronology
