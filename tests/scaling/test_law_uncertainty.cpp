// Draws and first-order propagation of a fitted law's covariance (law_uncertainty.hpp): the draws recover
// a known covariance, are reproducible, hold the constants without a covariance, stay inside the fit's
// ranges; the linearised variance is exact for a function linear in the drawn coordinates; percentiles.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/law_uncertainty.hpp"

namespace cs = craterkit::scaling;

namespace {

// H1, H2, mu with sigmas (in ln H1, ln H2, mu) 0.08, 0.1, 0.01 and strong correlations, as fits give them.
cs::LawCovariance known_covariance() {
  cs::LawCovariance c;
  c.law = {cs::Form::hh2011, 0.60, 0.25, 0.44, 0.4};
  c.names = {"H1", "H2", "mu"};
  c.fixed = {"nu"};
  const Eigen::Vector3d sigma(0.08, 0.1, 0.01);
  Eigen::Matrix3d correlation;
  correlation << 1.0, 0.9, -0.8, 0.9, 1.0, -0.95, -0.8, -0.95, 1.0;
  const Eigen::Matrix3d internal = sigma.asDiagonal() * correlation * sigma.asDiagonal();
  const Eigen::Vector3d natural_scale(0.60, 0.25, 1.0);  // sigma_c = c sigma_ln c
  c.covariance = natural_scale.asDiagonal() * internal * natural_scale.asDiagonal();
  return c;
}

}  // namespace

TEST(LawUncertainty, DrawsRecoverAKnownCovariance) {
  const auto c = known_covariance();
  const Eigen::MatrixXd expected = cs::internal_covariance(c);
  EXPECT_NEAR(std::sqrt(expected(0, 0)), 0.08, 1e-12);
  const int n = 20000;
  const auto samples = cs::sample_laws(c, n, 42);
  ASSERT_EQ(samples.laws.size(), static_cast<std::size_t>(n));
  EXPECT_EQ(samples.rejected, 0);  // mu 0.44 +- 0.01 stays inside [1/3, 2/3]
  Eigen::MatrixXd x(n, 3);
  for (int i = 0; i < n; ++i) {
    const auto& law = samples.laws[static_cast<std::size_t>(i)];
    x.row(i) << std::log(law.coefficient_1), std::log(law.coefficient_2), law.mu;
    EXPECT_EQ(law.nu, 0.4);  // held
  }
  const Eigen::RowVectorXd mean = x.colwise().mean();
  EXPECT_NEAR(mean(0), std::log(0.60), 4.0 * 0.08 / std::sqrt(n));
  EXPECT_NEAR(mean(2), 0.44, 4.0 * 0.01 / std::sqrt(n));
  const Eigen::MatrixXd centred = x.rowwise() - mean;
  const Eigen::MatrixXd sample = centred.transpose() * centred / (n - 1);
  for (int r = 0; r < 3; ++r) {
    // A variance from 20000 draws is known to 1 % (sqrt(2/n)); 4 % is 4 standard errors.
    EXPECT_NEAR(sample(r, r) / expected(r, r), 1.0, 0.04) << r;
    for (int k = 0; k < r; ++k) {
      const double rho = sample(r, k) / std::sqrt(sample(r, r) * sample(k, k));
      const double rho_expected = expected(r, k) / std::sqrt(expected(r, r) * expected(k, k));
      EXPECT_NEAR(rho, rho_expected, 0.01) << r << "," << k;
    }
  }
}

TEST(LawUncertainty, DrawsAreReproducibleAndZeroCovarianceDrawsTheFit) {
  const auto c = known_covariance();
  const auto a = cs::sample_laws(c, 50, 7);
  const auto b = cs::sample_laws(c, 50, 7);
  const auto other = cs::sample_laws(c, 50, 8);
  for (std::size_t i = 0; i < 50; ++i) {
    EXPECT_EQ(a.laws[i].coefficient_1, b.laws[i].coefficient_1);
    EXPECT_EQ(a.laws[i].mu, b.laws[i].mu);
  }
  EXPECT_NE(a.laws[0].mu, other.laws[0].mu);
  auto zero = c;
  zero.covariance.setZero();
  for (const auto& law : cs::sample_laws(zero, 20, 1).laws) {
    EXPECT_EQ(law.coefficient_1, c.law.coefficient_1);
    EXPECT_EQ(law.coefficient_2, c.law.coefficient_2);
    EXPECT_EQ(law.mu, c.law.mu);
  }
  EXPECT_EQ(cs::linearised_variance(zero, [](const cs::ScalingLaw& law) { return law.mu; }), 0.0);
  cs::LawCovariance none;
  none.law = c.law;
  EXPECT_FALSE(none.has_covariance());
  EXPECT_EQ(cs::sample_laws(none, 3, 1).laws.size(), 3u);
  EXPECT_THROW(cs::sample_laws(c, 0, 1), craterkit::InputError);
}

TEST(LawUncertainty, DrawsStayInsideTheFitsRanges) {
  auto c = known_covariance();
  c.law.mu = 0.34;  // 0.7 sigma above the lower bound 1/3
  const auto samples = cs::sample_laws(c, 2000, 3);
  EXPECT_GT(samples.rejected, 200);
  for (const auto& law : samples.laws) EXPECT_GE(law.mu, 1.0 / 3.0);
  c.law.mu = 0.2;  // far outside: almost every draw would be
  EXPECT_THROW(cs::sample_laws(c, 100, 3), craterkit::InputError);
}

TEST(LawUncertainty, LinearisedVarianceIsExactForALinearFunction) {
  const auto c = known_covariance();
  const Eigen::MatrixXd v = cs::internal_covariance(c);
  // f = ln H1 + 2 mu: var = V00 + 4 V22 + 4 V02.
  const double variance = cs::linearised_variance(
      c, [](const cs::ScalingLaw& law) { return std::log(law.coefficient_1) + 2.0 * law.mu; });
  EXPECT_NEAR(variance, v(0, 0) + 4.0 * v(2, 2) + 4.0 * v(0, 2), 1e-9 * v(0, 0));
  // A held constant contributes nothing.
  EXPECT_EQ(cs::linearised_variance(c, [](const cs::ScalingLaw& law) { return law.nu; }), 0.0);
}

TEST(LawUncertainty, Percentiles) {
  std::vector<double> values;
  for (int i = 0; i <= 100; ++i) values.push_back(100 - i);
  const auto p = cs::percentiles(values);
  EXPECT_NEAR(p.p50, 50.0, 1e-12);
  EXPECT_NEAR(p.p16, 15.8655, 1e-9);
  EXPECT_NEAR(p.p84, 84.1345, 1e-9);
  EXPECT_THROW(cs::percentiles({}), craterkit::InputError);
}
