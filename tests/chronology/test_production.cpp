// Crater production and relative rates against closed forms derived by hand for an inverse scaling law
// a = R / k (R/a constant, as in the pure strength regime) and a single power-law population.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "craterkit/chronology/production.hpp"
#include "craterkit/chronology/relative_rates.hpp"
#include "craterkit/common/input_error.hpp"

namespace ck = craterkit::chronology;

namespace {

// Crater-to-impactor radius ratio k: a = R / k, at any speed.
ck::ImpactorRadiusFunction constant_ratio(double k) {
  return [k](double R, double) { return R / k; };
}

ck::ProductionSetup setup_power_law(double q, ck::CrossSection cs) {
  ck::ProductionSetup s;
  s.population = ck::power_law_population(q, 1.0, 1e8);  // N(>1 m) = 1e8
  s.intrinsic_probability = ck::per_square_metre(2.86e-18);
  s.target_radius = 448.0;
  s.surface_area = 4.0 * M_PI * 448.0 * 448.0;
  s.speeds = ck::single_speed(5000.0);
  s.diameter.rim_to_apparent = 1.25;
  s.cross_section = cs;
  return s;
}

}  // namespace

TEST(Production, ClosedFormSinglePowerLaw) {
  const auto s = setup_power_law(-3.5, ck::CrossSection::target_plus_impactor);
  const double D = 30.0, k = 10.0;
  const double a = D / (2.0 * 1.25) / k;  // 1.2 m
  const double expected = 2.86e-24 * std::pow(448.0 + a, 2) * 1e8 * std::pow(a, -2.5) / s.surface_area;
  EXPECT_NEAR(ck::crater_production_rate(s, constant_ratio(k), D), expected, 1e-12 * expected);
}

TEST(Production, DifferentialMatchesCumulativeSlope) {
  // Target-only cross-section: r(D) = C D^(q+1), so -dr/dD = -(q+1) r / D exactly.
  const auto s = setup_power_law(-4.0, ck::CrossSection::target_only);
  const auto law = constant_ratio(25.0);
  for (double D : {5.0, 20.0, 150.0}) {
    const double r = ck::crater_production_rate(s, law, D);
    EXPECT_NEAR(ck::differential_production_rate(s, law, D), 3.0 * r / D, 1e-6 * 3.0 * r / D);
  }
}

TEST(Production, SpeedDistributionIsTheWeightedMean) {
  auto s = setup_power_law(-4.0, ck::CrossSection::target_only);
  // R/a grows with speed as U^0.5 here (an arbitrary but exact law for the test).
  const ck::ImpactorRadiusFunction law = [](double R, double U) {
    return R / (10.0 * std::sqrt(U / 5000.0));
  };
  s.speeds = ck::SpeedDistribution{{3000.0, 5000.0, 8000.0}, {1.0, 2.0, 1.0}};
  const double D = 40.0;
  double expected = 0.0;
  for (auto [U, w] : {std::pair{3000.0, 0.25}, std::pair{5000.0, 0.5}, std::pair{8000.0, 0.25}}) {
    auto one = s;
    one.speeds = ck::single_speed(U);
    expected += w * ck::crater_production_rate(one, law, D);
  }
  EXPECT_NEAR(ck::crater_production_rate(s, law, D), expected, 1e-13 * expected);
}

TEST(RelativeRates, HundredAgainstTenWithQMinus4GivesThousand) {
  // docs/physics.md sec. 7: D_crat/D_proj of 100 instead of 10 gives 10^3 more craters when q = -4.
  const auto s = setup_power_law(-4.0, ck::CrossSection::target_only);
  for (double D : {10.0, 36.0, 300.0}) {
    const auto rr = ck::relative_rate(s, constant_ratio(10.0), constant_ratio(100.0), D);
    EXPECT_NEAR(rr.ratio, 1000.0, 1000.0 * 1e-12) << D;
    EXPECT_NEAR(rr.impactor_radius_a / rr.impactor_radius_b, 10.0, 1e-12);
  }
}

TEST(RelativeRates, ImpactorCrossSectionAddsItsGeometricFactor) {
  const auto s = setup_power_law(-4.0, ck::CrossSection::target_plus_impactor);
  const double D = 200.0;
  const auto rr = ck::relative_rate(s, constant_ratio(10.0), constant_ratio(100.0), D);
  const double a1 = D / 2.5 / 10.0, a2 = D / 2.5 / 100.0;
  EXPECT_NEAR(rr.ratio, 1000.0 * std::pow((448.0 + a2) / (448.0 + a1), 2), 1e-9);
}

TEST(RelativeRates, GeneralSlopeClosedForm) {
  // ratio = (a_B/a_A)^(q+1) = (k_A/k_B)^(q+1)
  for (double q : {-2.5, -3.0, -4.2}) {
    const auto s = setup_power_law(q, ck::CrossSection::target_only);
    const auto rr = ck::relative_rate(s, constant_ratio(12.0), constant_ratio(31.0), 50.0);
    EXPECT_NEAR(rr.ratio, std::pow(12.0 / 31.0, q + 1.0), 1e-12 * rr.ratio) << q;
  }
}

TEST(Production, BadSpeedTableIsAnError) {
  EXPECT_THROW(ck::validate(ck::SpeedDistribution{{5000.0, -1.0}, {1.0, 1.0}}), craterkit::InputError);
  EXPECT_THROW(ck::validate(ck::SpeedDistribution{{5000.0}, {0.0}}), craterkit::InputError);
}

TEST(Production, SpeedTableFileAndItsErrors) {
  const auto dir = std::filesystem::temp_directory_path();
  const auto good = (dir / "ck_speeds.csv").string();
  std::ofstream(good) << "# speeds\nspeed_km_s,weight\n3,1\n5.3,2\n";
  const auto s = ck::read_speed_distribution(good);
  ASSERT_EQ(s.speed.size(), 2u);
  EXPECT_DOUBLE_EQ(s.speed[1], 5300.0);
  EXPECT_NEAR(ck::mean_speed(s), (3000.0 + 2.0 * 5300.0) / 3.0, 1e-9);
  const auto bad = (dir / "ck_speeds_bad.csv").string();
  std::ofstream(bad) << "speed_m_s,weight\n3000,1\n5300,x\n";
  try {
    ck::read_speed_distribution(bad);
    FAIL();
  } catch (const craterkit::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ck_speeds_bad.csv:3"), std::string::npos) << e.what();
  }
}

TEST(Conventions, RimDiameterAndCapChecks) {
  ck::DiameterConvention c;
  c.rim_to_apparent = 1.21;
  EXPECT_DOUBLE_EQ(ck::rim_diameter_from_apparent_radius(7.25, c), 2.0 * 7.25 * 1.21);
  EXPECT_DOUBLE_EQ(ck::apparent_radius_from_rim_diameter(ck::rim_diameter_from_apparent_radius(7.25, c), c),
                   7.25);
  c.rim_to_apparent = 0.8;
  EXPECT_THROW(ck::validate(c, "--rim-to-apparent"), craterkit::InputError);
  ck::EquilibriumCap cap;
  EXPECT_DOUBLE_EQ(ck::expected_cumulative_density(cap, 10.0, 1e6, 1e-9), 1e-3);  // off: t r
  cap.enabled = true;
  cap.fraction_of_geometric = 0.1;
  const double n_eq = 0.1 * 1.54 / 100.0;
  EXPECT_NEAR(ck::expected_cumulative_density(cap, 10.0, 1e12, 1e-9), n_eq, 1e-15);      // saturated
  EXPECT_NEAR(ck::expected_cumulative_density(cap, 10.0, 1.0, 1e-9) / 1e-9, 1.0, 1e-6);  // linear limit
  cap.fraction_of_geometric = 1.5;
  EXPECT_THROW(ck::validate(cap), craterkit::InputError);
}
