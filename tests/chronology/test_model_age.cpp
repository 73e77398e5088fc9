// Model ages: the Poisson-likelihood density against its closed form (a Gamma density), coverage of the
// 1- and 2-sigma intervals over many seeded synthetic populations, binned against unbinned input, the
// equilibrium cap in its linear limit and the classical cumulative fit.
#include <gsl/gsl_cdf.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "craterkit/chronology/model_age.hpp"
#include "craterkit/common/input_error.hpp"

namespace ck = craterkit::chronology;

namespace {

// r(D) = c D^-b per m^2 per year (an exact power-law production function, D in m).
ck::ProductionFunction power_production(double c, double b) {
  return [c, b](double d) { return c * std::pow(d, -b); };
}

// Draws a crater population of age t: Poisson number in [dmin, inf), diameters from the truncated power law.
ck::CraterCounts synthetic(std::mt19937_64& rng, double area, double t, double c, double b, double dmin) {
  ck::CraterCounts counts;
  counts.source = "synthetic";
  counts.area = area;
  std::poisson_distribution<int> poisson(area * t * c * std::pow(dmin, -b));
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int k = poisson(rng);
  for (int i = 0; i < k; ++i) {
    counts.diameters.push_back(dmin * std::pow(1.0 - u(rng), -1.0 / b));
    counts.fractions.push_back(1.0);
  }
  return counts;
}

}  // namespace

TEST(ModelAge, DensityIsTheGammaDensityWithoutCap) {
  std::mt19937_64 rng(7);
  const double area = 1e6, c = 1e-6, b = 2.5, dmin = 10.0;
  const auto counts = synthetic(rng, area, 1e7, c, b, dmin);
  const double k = static_cast<double>(counts.diameters.size());
  ASSERT_GT(k, 20.0);
  ck::AgeFitOptions opt;
  opt.min_diameter = dmin;
  const auto age = ck::fit_model_age(counts, power_production(c, b), opt);
  // Posterior with a uniform prior: Gamma(shape k+1, scale 1/(A r(Dmin))); its CDF at the reported
  // quantiles must be the quantile levels.
  const double scale = 1.0 / (area * c * std::pow(dmin, -b));
  EXPECT_NEAR(gsl_cdf_gamma_P(age.median, k + 1.0, scale), 0.5, 1e-5);
  EXPECT_NEAR(gsl_cdf_gamma_P(age.sigma1_low, k + 1.0, scale), 0.158655, 1e-5);
  EXPECT_NEAR(gsl_cdf_gamma_P(age.sigma1_high, k + 1.0, scale), 0.841345, 1e-5);
  EXPECT_NEAR(gsl_cdf_gamma_P(age.sigma2_low, k + 1.0, scale), 0.0227501, 1e-5);
  EXPECT_NEAR(gsl_cdf_gamma_P(age.sigma2_high, k + 1.0, scale), 0.9772499, 1e-5);
  EXPECT_NEAR(age.mode / (k * scale), 1.0, 2e-3);  // grid resolution
  EXPECT_DOUBLE_EQ(age.craters_in_range, k);
}

TEST(ModelAge, SyntheticPopulationsRecoverTheirAgeWithNominalCoverage) {
  const double area = 2.7e6, c = 3e-9, b = 2.2, dmin = 20.0, t_true = 8.9e6;
  // Expected craters in range: A t c dmin^-b ~ 100.
  int inside1 = 0, inside2 = 0;
  const int seeds = 400;
  for (int seed = 1; seed <= seeds; ++seed) {
    std::mt19937_64 rng(static_cast<std::uint64_t>(seed));
    const auto counts = synthetic(rng, area, t_true, c, b, dmin);
    ck::AgeFitOptions opt;
    opt.min_diameter = dmin;
    opt.grid_points = 501;
    const auto age = ck::fit_model_age(counts, power_production(c, b), opt);
    inside1 += (t_true >= age.sigma1_low && t_true <= age.sigma1_high) ? 1 : 0;
    inside2 += (t_true >= age.sigma2_low && t_true <= age.sigma2_high) ? 1 : 0;
  }
  std::printf("coverage over %d seeds: 1-sigma %.3f, 2-sigma %.3f\n", seeds, inside1 / double(seeds),
              inside2 / double(seeds));
  // Binomial with p = 0.683 (0.954) over 400 seeds: standard deviation 0.023 (0.010); allow 3.5 sigma.
  EXPECT_NEAR(inside1 / double(seeds), 0.683, 3.5 * 0.023);
  EXPECT_NEAR(inside2 / double(seeds), 0.954, 3.5 * 0.0105);
}

TEST(ModelAge, OneBinnedCountEqualsUnbinned) {
  std::mt19937_64 rng(3);
  const double area = 5e5, c = 2e-5, b = 3.0, dmin = 15.0;
  auto counts = synthetic(rng, area, 3e7, c, b, dmin);
  ck::AgeFitOptions opt;
  opt.min_diameter = dmin;
  const auto unbinned = ck::fit_model_age(counts, power_production(c, b), opt);
  ck::CraterCounts binned;
  binned.source = "binned";
  binned.area = area;
  binned.bins = {{dmin, static_cast<double>(counts.diameters.size())}};
  const auto from_bins = ck::fit_model_age(binned, power_production(c, b), opt);
  EXPECT_NEAR(from_bins.median / unbinned.median, 1.0, 1e-6);
  EXPECT_NEAR(from_bins.sigma1_high / unbinned.sigma1_high, 1.0, 1e-6);
}

TEST(ModelAge, SeveralBinsGiveTheSameGammaPosterior) {
  // With linear production the bin split does not matter: the posterior depends on the total count only.
  const double area = 1e6, c = 1e-5, b = 2.0;
  ck::CraterCounts binned;
  binned.source = "bins";
  binned.area = area;
  binned.bins = {{10.0, 50.0}, {20.0, 14.0}, {40.0, 3.0}};
  const auto age = ck::fit_model_age(binned, power_production(c, b), {});
  const double scale = 1.0 / (area * c * std::pow(10.0, -b));
  EXPECT_NEAR(gsl_cdf_gamma_P(age.median, 51.0, scale), 0.5, 1e-5);
}

TEST(ModelAge, CapInItsLinearLimitChangesNothing) {
  std::mt19937_64 rng(11);
  const double area = 1e7, c = 1e-10, b = 3.0, dmin = 10.0;
  const auto counts = synthetic(rng, area, 1e8, c, b, dmin);  // about 100 craters
  ck::AgeFitOptions opt;
  opt.min_diameter = dmin;
  const auto plain = ck::fit_model_age(counts, power_production(c, b), opt);
  opt.cap.enabled = true;
  opt.cap.fraction_of_geometric = 1.0;  // N_eq(10 m) = 1.5e-2 m^-2 against t r = 1e-5 m^-2: linear regime
  const auto capped = ck::fit_model_age(counts, power_production(c, b), opt);
  EXPECT_NEAR(capped.median / plain.median, 1.0, 2e-3);
}

TEST(ModelAge, CapMakesSaturatedCountsOlder) {
  // Counts near equilibrium need a much longer time under the cap than the linear model says.
  const double area = 1e4, c = 1e-4, b = 2.0, dmin = 5.0;
  ck::CraterCounts counts;
  counts.source = "dense";
  counts.area = area;
  counts.bins = {{dmin, 0.5 * 0.05 * 1.54 / (dmin * dmin) * area}};  // half of N_eq at 5% of geometric
  ck::AgeFitOptions opt;
  opt.grid_points = 20001;  // the capped density spreads over many decades up to the maximum age
  const auto plain = ck::fit_model_age(counts, power_production(c, b), opt);
  opt.cap.enabled = true;
  const auto capped = ck::fit_model_age(counts, power_production(c, b), opt);
  // N = N_eq (1 - exp(-t r / N_eq)) = N_eq / 2  =>  t = ln 2 N_eq / r, against N_eq / (2 r) linear.
  EXPECT_NEAR(capped.mode / plain.mode, 2.0 * std::log(2.0), 0.02);
  EXPECT_TRUE(capped.reaches_max_age);  // a count below equilibrium still allows any older age
  EXPECT_FALSE(plain.reaches_max_age);
}

TEST(ModelAge, CumulativeFitOfExactCounts) {
  // Craters placed exactly on the isochron N(>=D) = t r(D): the cumulative fit returns t.
  const double area = 1e6, c = 1e-6, b = 2.0, t = 5e7;
  ck::CraterCounts counts;
  counts.source = "exact";
  counts.area = area;
  for (int i = 1; i <= 60; ++i) {
    counts.diameters.push_back(std::pow(i / (area * t * c), -1.0 / b));  // N(>=D_i) = i
    counts.fractions.push_back(1.0);
  }
  const auto age = ck::fit_model_age(counts, power_production(c, b), {});
  EXPECT_NEAR(age.cumulative_fit_age / t, 1.0, 1e-9);
  EXPECT_NEAR(age.cumulative_fit_sigma / (t / std::sqrt(60.0)), 1.0, 1e-9);
}

TEST(ModelAge, EmptyRangeIsAnError) {
  ck::CraterCounts counts;
  counts.source = "few";
  counts.area = 1e6;
  counts.bins = {{10.0, 5.0}};
  ck::AgeFitOptions opt;
  opt.min_diameter = 50.0;
  EXPECT_THROW(ck::fit_model_age(counts, power_production(1e-6, 2.0), opt), craterkit::InputError);
}

TEST(ModelAge, FractionsWeightOrCountWhole) {
  // Half of the craters counted with fraction 0.5: weighted, k = sum f; whole, k = n (craterstats' Poisson
  // fit). Either way the posterior is the Gamma density of shape k + 1.
  std::mt19937_64 rng(11);
  const double area = 1e6, c = 1e-6, b = 2.5, dmin = 10.0;
  auto counts = synthetic(rng, area, 1e7, c, b, dmin);
  for (std::size_t i = 0; i < counts.fractions.size(); i += 2) counts.fractions[i] = 0.5;
  const double n = static_cast<double>(counts.diameters.size());
  double weighted = 0.0;
  for (double f : counts.fractions) weighted += f;
  ASSERT_LT(weighted, n - 5.0);
  const double scale = 1.0 / (area * c * std::pow(dmin, -b));
  ck::AgeFitOptions opt;
  opt.min_diameter = dmin;
  for (const bool weight : {true, false}) {
    opt.weight_by_fraction = weight;
    const auto age = ck::fit_model_age(counts, power_production(c, b), opt);
    const double k = weight ? weighted : n;
    EXPECT_DOUBLE_EQ(age.craters_in_range, k) << weight;
    EXPECT_NEAR(gsl_cdf_gamma_P(age.median, k + 1.0, scale), 0.5, 1e-5) << weight;
  }
}
