// Chronology systems (production polynomial and N(1)(t)): the closed forms, the clock in the likelihood
// (the posterior of the equivalent constant-flux time is the Gamma density), and ages of a count against
// craterstats 3.6.10 run on the same file.
#include <gsl/gsl_cdf.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "craterkit/chronology/chronology_system.hpp"
#include "craterkit/chronology/crater_counts.hpp"
#include "craterkit/chronology/model_age.hpp"
#include "craterkit/common/input_error.hpp"

namespace ck = craterkit::chronology;

namespace {

const std::string kSyntheticUnit = std::string(CRATERKIT_TEST_DATA) + "/synthetic_lunar_unit.diam";

ck::AgeEstimate date(const ck::ChronologySystem& system, const ck::CraterCounts& counts, double d_min,
                     double d_max, bool weight, bool density_prior) {
  ck::AgeFitOptions options;
  options.min_diameter = d_min;
  options.max_diameter = d_max;
  options.weight_by_fraction = weight;
  options.prior_uniform_in_density = density_prior;
  options.clock = ck::chronology_clock(system);
  return ck::fit_model_age(counts, ck::chronology_production(system), options);
}

}  // namespace

TEST(ChronologySystems, ShippedSystemsAndTheirClosedForms) {
  const auto names = ck::chronology_system_names();
  ASSERT_GE(names.size(), 2u);
  const auto moon = ck::load_chronology_system("moon_neukum2001");
  EXPECT_EQ(moon.body, "Moon");
  EXPECT_EQ(moon.production.size(), 12u);
  EXPECT_DOUBLE_EQ(moon.min_diameter, 10.0);
  const double n1_3gyr = 5.44e-14 * (std::exp(6.93 * 3.0) - 1.0) + 8.38e-4 * 3.0;
  EXPECT_NEAR(ck::n1(moon, 3e9) / n1_3gyr, 1.0, 1e-13);
  EXPECT_NEAR(ck::cumulative_density(moon, 1000.0, 3e9) / n1_3gyr, 1.0, 1e-13);  // F(1 km) = 1
  // The polynomial by hand at D = 10 km: log10 N = sum a_n (log10 10)^n = sum a_n.
  double sum = 0.0;
  for (std::size_t n = 1; n < moon.production.size(); ++n) sum += moon.production[n];
  EXPECT_NEAR(ck::cumulative_density(moon, 10e3, 1e9) / (ck::n1(moon, 1e9) * std::pow(10.0, sum)), 1.0,
              1e-12);
  // Present-day production and the clock: young ages run at the present rate.
  const auto clock = ck::chronology_clock(moon);
  EXPECT_NEAR(clock(1e6) / 1e6, 1.0, 1e-5);
  EXPECT_GT(clock(4e9), 1.5 * 4e9);  // the early bombardment
  const auto r = ck::chronology_production(moon);
  EXPECT_NEAR(r(1000.0) * clock(2e9) * 1e6, ck::cumulative_density(moon, 1000.0, 2e9), 1e-12 * n1_3gyr);
  EXPECT_THROW(r(5.0), craterkit::InputError);  // below the polynomial's 10 m
  EXPECT_EQ(ck::load_chronology_system("mars_neukum_ivanov2001").body, "Mars");
  EXPECT_THROW(ck::load_chronology_system("venus"), craterkit::InputError);
}

TEST(ChronologySystems, DensityPriorMakesTheEquivalentTimeGammaDistributed) {
  // With a prior uniform in crater density the equivalent constant-flux time clock(t) has the Gamma
  // density of shape k + 1: its quantiles map to the age quantiles through the clock.
  const auto moon = ck::load_chronology_system("moon_neukum2001");
  const auto counts = ck::read_crater_counts(kSyntheticUnit);
  const double d_min = 200.0, d_max = 1000.0;
  const auto age = date(moon, counts, d_min, d_max, false, true);
  const auto r = ck::chronology_production(moon);
  const double scale = 1.0 / (counts.area * (r(d_min) - r(d_max)));
  const double k = age.craters_in_range;
  EXPECT_EQ(k, 60.0);
  const auto clock = ck::chronology_clock(moon);
  EXPECT_NEAR(gsl_cdf_gamma_P(clock(age.median), k + 1.0, scale), 0.5, 2e-4);
  EXPECT_NEAR(gsl_cdf_gamma_P(clock(age.sigma1_low), k + 1.0, scale), 0.158655, 2e-4);
  EXPECT_NEAR(gsl_cdf_gamma_P(clock(age.sigma1_high), k + 1.0, scale), 0.841345, 2e-4);
}

TEST(ChronologySystems, AgesMatchCraterstats) {
  // craterstats 3.6.10 (Craterpdf, its Poisson age) on tests/chronology/data/synthetic_lunar_unit.diam:
  // median and 1-sigma bounds in Gyr. craterstats counts every crater once and puts a prior uniform in
  // crater density; its likelihood grid (steps of 0.003 in log10 N(1)) reads ages about 0.35 % low where
  // N(1) grows linearly, so 0.6 % is allowed.
  struct Case {
    const char* system;
    double d_min_km, d_max_km, k, median, low, high;
  };
  const Case cases[] = {
      {"moon_neukum2001", 0.2, 1.0, 60, 0.81299883, 0.71306909, 0.92184374},
      {"moon_neukum2001", 0.15, 3.0, 160, 0.81791096, 0.75509433, 0.88414648},
      {"mars_neukum_ivanov2001", 0.2, 1.0, 60, 1.47151, 1.29063106, 1.66853938},
  };
  const auto counts = ck::read_crater_counts(kSyntheticUnit);
  for (const auto& c : cases) {
    const auto system = ck::load_chronology_system(c.system);
    const auto age = date(system, counts, c.d_min_km * 1e3, c.d_max_km * 1e3, false, true);
    EXPECT_EQ(age.craters_in_range, c.k) << c.system;
    EXPECT_NEAR(age.median / 1e9 / c.median, 1.0, 6e-3) << c.system << " " << c.d_min_km;
    EXPECT_NEAR(age.sigma1_low / 1e9 / c.low, 1.0, 6e-3) << c.system << " " << c.d_min_km;
    EXPECT_NEAR(age.sigma1_high / 1e9 / c.high, 1.0, 6e-3) << c.system << " " << c.d_min_km;
    // craterkit's default weights the half-counted craters by their fraction: fewer craters, a younger age.
    const auto weighted = date(system, counts, c.d_min_km * 1e3, c.d_max_km * 1e3, true, true);
    EXPECT_LT(weighted.craters_in_range, c.k - 5.0);
    EXPECT_LT(weighted.median, 0.95 * age.median);
  }
}
