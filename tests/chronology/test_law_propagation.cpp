// The scaling law's uncertainty through the chronology (law_propagation.hpp), with the covariance of a real
// fit to synthetic data: the spread of impactor radii and relative rates over the draws matches the
// linearised one; a model age reports the counting and the law term, and they add up to the total; with a
// zero covariance the law term is exactly zero.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "craterkit/chronology/law_propagation.hpp"
#include "craterkit/chronology/scaled_production.hpp"
#include "craterkit/scaling/fit.hpp"
#include "craterkit/scaling/law_uncertainty.hpp"

namespace ck = craterkit::chronology;
namespace sc = craterkit::scaling;

namespace {

// A well-determined fit: 64 synthetic impacts (4 masses, 2 impactor densities, 4 strengths, 2 speeds) from
// the Jutzi et al. (2022) constants with 5 % log-normal noise, fitted in the HH2011 form.
sc::LawCovariance fitted_covariance() {
  const sc::ScalingLaw truth{sc::Form::hh2011, 0.60, 0.25, 0.44, 0.4};
  std::mt19937_64 random(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  sc::RadiiTable table;
  table.source = "synthetic";
  int line = 1;
  for (double delta : {2700.0, 7800.0}) {
    for (double mass : {0.05, 2.0, 100.0, 2000.0}) {
      for (double y : {0.05, 0.5, 5.0, 50.0}) {
        for (double u : {1000.0, 4000.0}) {
          sc::ImpactRecord row;
          row.impactor = {std::cbrt(3.0 * mass / (4.0 * std::numbers::pi * delta)), delta, u};
          row.target = {1300.0, 1.4e-4, y};
          row.crater_radius =
              sc::crater_radius(truth, row.impactor, row.target) * std::exp(0.05 * normal(random));
          row.crater_radius_sigma = 0.05 * row.crater_radius;
          row.line = ++line;
          table.rows.push_back(row);
        }
      }
    }
  }
  sc::FitOptions options;
  options.form = sc::Form::hh2011;
  return sc::law_covariance(sc::fit_scaling_law(table, options));
}

// Normalised (1e20 impactors larger than 1 m) so that the counts below are about a million years old, far
// from the prior's upper end, where the age would be set by the prior instead of the law.
ck::ProductionSetup setup() {
  ck::ProductionSetup s;
  s.population = ck::power_law_population(-3.5, 1.0, 1e20);
  s.intrinsic_probability = ck::per_square_metre(2.86e-18);
  s.target_radius = 448.0;
  s.surface_area = 2.7e6;
  s.speeds = ck::single_speed(5300.0);
  s.cross_section = ck::CrossSection::target_only;
  return s;
}

constexpr double kDensity = 2600.0;  // impactor density, kg/m^3
const sc::Target kWeak{1190.0, 1.5e-4, 0.05};
const sc::Target kStrong{1190.0, 1.5e-4, 1.0};

double rate(const sc::ScalingLaw& law, const sc::Target& target, double d) {
  return ck::crater_production_rate(setup(), ck::scaled_impactor_radius(law, target, kDensity), d);
}

double standard_deviation(const std::vector<double>& values) {
  double mean = 0.0;
  for (double v : values) mean += v / static_cast<double>(values.size());
  double sum = 0.0;
  for (double v : values) sum += (v - mean) * (v - mean);
  return std::sqrt(sum / static_cast<double>(values.size() - 1));
}

// 77 craters >= 20 m on 2.7 km^2, as one cumulative bin (the Ryugu count of Hirata et al. 2020).
ck::CraterCounts ryugu_like_counts() {
  ck::CraterCounts counts;
  counts.source = "test";
  counts.area = 2.7e6;
  counts.bins = {{20.0, 77.0}};
  return counts;
}

}  // namespace

TEST(LawPropagation, SampledSpreadOfRatesMatchesTheLinearisedOne) {
  const auto covariance = fitted_covariance();
  ASSERT_EQ(covariance.names.size(), 4u);  // H1, H2, mu, nu all determined
  const double d = 20.0;
  const auto relative = [&](const sc::ScalingLaw& law) {
    return rate(law, kStrong, d) / rate(law, kWeak, d);
  };
  const auto impactor = [&](const sc::ScalingLaw& law) {
    return ck::scaled_impactor_radius(law, kStrong, kDensity)(d / 2.4, 5300.0);
  };
  const double linear_relative = std::sqrt(sc::linearised_variance(covariance, relative));
  const double linear_impactor = std::sqrt(sc::linearised_variance(covariance, impactor));
  ASSERT_GT(linear_relative, 0.0);

  // 4000 draws: a standard deviation to 1.1 % (1/sqrt(2n)); a few % is several standard errors.
  const auto draws = sc::sample_laws(covariance, 4000, 5);
  std::vector<double> relatives, impactors;
  for (const auto& law : draws.laws) {
    relatives.push_back(relative(law));
    impactors.push_back(impactor(law));
  }
  EXPECT_NEAR(standard_deviation(relatives) / linear_relative, 1.0, 0.04);
  EXPECT_NEAR(standard_deviation(impactors) / linear_impactor, 1.0, 0.04);

  // rate_spread gives the same draws' percentiles: half the 16-84 range is about one sigma, the median the
  // central value.
  const auto spread = ck::rate_spread(setup(), draws.laws, kStrong, kWeak, kDensity, d);
  EXPECT_NEAR((spread.relative_rate.p84 - spread.relative_rate.p16) / 2.0 / linear_relative, 1.0, 0.06);
  EXPECT_NEAR(spread.relative_rate.p50, relative(covariance.law), 0.1 * linear_relative);
  EXPECT_NEAR((spread.impactor_radius.p84 - spread.impactor_radius.p16) / 2.0 / linear_impactor, 1.0, 0.06);
}

TEST(LawPropagation, AgeReportsCountingAndLawUncertainty) {
  const auto covariance = fitted_covariance();
  const auto counts = ryugu_like_counts();
  const ck::AgeFitOptions options;
  const auto central = ck::fit_model_age(
      counts, ck::production_function(setup(), ck::scaled_impactor_radius(covariance.law, kWeak, kDensity)),
      options);
  const auto draws = sc::sample_laws(covariance, 1000, 9);
  const auto spread = ck::model_age_spread(counts, setup(), draws.laws, kWeak, kDensity, options);

  // The law term: with one bin and no cap the median age is a constant over r(20 m), so its percentiles
  // are those of 1/r over the same draws.
  std::vector<double> rates;
  for (const auto& law : draws.laws) rates.push_back(rate(law, kWeak, 20.0));
  const auto r = sc::percentiles(rates);
  const double constant = central.median * rate(covariance.law, kWeak, 20.0);
  EXPECT_NEAR(spread.median.p16 * r.p84 / constant, 1.0, 2e-3);
  EXPECT_NEAR(spread.median.p84 * r.p16 / constant, 1.0, 2e-3);
  EXPECT_LT(spread.median.p16, central.median);
  EXPECT_GT(spread.median.p84, central.median);

  // The total is wider than either term, and (both terms being close to log-normal) its 1-sigma half-width
  // in ln t is close to the quadrature sum of theirs.
  const double counting = std::log(central.sigma1_high / central.sigma1_low) / 2.0;
  const double law = std::log(spread.median.p84 / spread.median.p16) / 2.0;
  const double total = std::log(spread.total_sigma1_high / spread.total_sigma1_low) / 2.0;
  EXPECT_GT(law, 0.01);
  EXPECT_GT(total, counting);
  EXPECT_GT(total, law);
  EXPECT_NEAR(total / std::hypot(counting, law), 1.0, 0.08);
  EXPECT_LT(spread.total_sigma2_low, spread.total_sigma1_low);
  EXPECT_GT(spread.total_sigma2_high, spread.total_sigma1_high);
}

TEST(LawPropagation, ZeroCovarianceGivesNoLawTerm) {
  auto covariance = fitted_covariance();
  covariance.covariance.setZero();
  const auto counts = ryugu_like_counts();
  const ck::AgeFitOptions options;
  const auto central = ck::fit_model_age(
      counts, ck::production_function(setup(), ck::scaled_impactor_radius(covariance.law, kWeak, kDensity)),
      options);
  const auto draws = sc::sample_laws(covariance, 100, 1);
  const auto spread = ck::model_age_spread(counts, setup(), draws.laws, kWeak, kDensity, options);
  EXPECT_EQ(spread.median.p16, central.median);
  EXPECT_EQ(spread.median.p84, central.median);
  // The total is then the counting uncertainty alone (to the resolution of the pooled quantiles).
  EXPECT_NEAR(spread.total_median / central.median, 1.0, 1e-3);
  EXPECT_NEAR(spread.total_sigma1_low / central.sigma1_low, 1.0, 1e-3);
  EXPECT_NEAR(spread.total_sigma1_high / central.sigma1_high, 1.0, 1e-3);
  EXPECT_NEAR(spread.total_sigma2_low / central.sigma2_low, 1.0, 2e-3);
  EXPECT_NEAR(spread.total_sigma2_high / central.sigma2_high, 1.0, 2e-3);
  const auto rates = ck::rate_spread(setup(), draws.laws, kStrong, kWeak, kDensity, 20.0);
  EXPECT_EQ(rates.relative_rate.p16, rates.relative_rate.p84);
}
