// The fit's uncertainty against resampling: Ceres's covariance against a bootstrap of the rows, and the
// coverage of its 2-sigma intervals over fresh noise on a known law (260 fits; a statistical validation, so
// labelled physics: 50x slower under the sanitizers than the 1 s it takes in a release build).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "craterkit/scaling/fit.hpp"
#include "scaling/synthetic_radii.hpp"

namespace cs = craterkit::scaling;

namespace {

using namespace scaling_test;

TEST(Fit, CovarianceAgreesWithBootstrapAndMonteCarloCoverage) {
  const Grid grid;
  const auto table = synthetic(truth_hh(), grid, 2);
  cs::FitOptions options;
  options.form = cs::Form::hh2011;
  const auto reference = cs::fit_scaling_law(table, options);

  cs::FitOptions quick = options;
  quick.starts = 2;

  // Non-parametric bootstrap: resample rows with replacement and refit.
  constexpr int kBootstrap = 200;
  std::mt19937_64 random(99);
  std::uniform_int_distribution<std::size_t> pick(0, table.rows.size() - 1);
  std::vector<std::vector<double>> samples(4);
  for (int b = 0; b < kBootstrap; ++b) {
    cs::RadiiTable resampled;
    resampled.source = "bootstrap";
    for (std::size_t i = 0; i < table.rows.size(); ++i) resampled.rows.push_back(table.rows[pick(random)]);
    const auto fit = cs::fit_scaling_law(resampled, quick);
    for (int k = 0; k < 4; ++k) samples[k].push_back(fit.parameters[k].value);
  }
  for (int k = 0; k < 4; ++k) {
    const auto& s = samples[k];
    double mean = 0.0;
    for (double v : s) mean += v / s.size();
    double variance = 0.0;
    for (double v : s) variance += (v - mean) * (v - mean) / (s.size() - 1);
    const double bootstrap_sigma = std::sqrt(variance);
    SCOPED_TRACE(reference.parameters[k].name);
    // 200 resamples estimate a sigma to about 5 %; allow 25 % for that and the model's non-linearity.
    EXPECT_NEAR(bootstrap_sigma / reference.parameters[k].sigma, 1.0, 0.25)
        << "bootstrap " << bootstrap_sigma << " Ceres " << reference.parameters[k].sigma;
  }

  // Monte Carlo: fresh noise on the true law; each parameter's truth must fall inside its 2-sigma
  // interval in about 95 % of the fits.
  constexpr int kRealisations = 60;
  std::vector<int> covered(4, 0);
  for (int seed = 0; seed < kRealisations; ++seed) {
    const auto fit = cs::fit_scaling_law(synthetic(truth_hh(), grid, 1000 + seed), quick);
    for (int k = 0; k < 4; ++k) {
      const auto& p = fit.parameters[k];
      if (std::abs(p.value - truth_value(truth_hh(), p.name)) < 2.0 * p.sigma) ++covered[k];
    }
  }
  for (int k = 0; k < 4; ++k) {
    SCOPED_TRACE(reference.parameters[k].name);
    // Binomial(60, 0.95): fewer than 52 has probability below 1 %.
    EXPECT_GE(covered[k], 52);
  }
}

}  // namespace
