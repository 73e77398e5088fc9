#pragma once
// The uncertainty of a fitted law's constants and the means to carry it into anything computed from the
// law (docs/chronology.md, "Scaling-law uncertainty").
//
// A fit gives the constants c1, c2 (K1, K2 or H1, H2), mu, nu with the covariance of the free, determined
// ones (fit.hpp). Fixed constants and those the fit could not determine are held at their values (so the
// spread of an undetermined one is NOT included; the caller reports that). The fit works in ln c1, ln c2,
// mu, nu, and its covariance is a first-order transform of the covariance in those coordinates
// (sigma_c = c sigma_ln c); the inverse transform gives that covariance back exactly, and it is in those
// coordinates that the constants are drawn and differentiated, so that coefficients stay positive.
//
// Two ways to carry the covariance into a quantity f(law):
//  - sampling (what the commands use): draws from the multivariate normal of the free constants, seeded
//    and reproducible (a Mersenne Twister, mt19937_64, and Box-Muller, both fully specified, so the draws are
//    the same on every platform); draws outside the ranges the fit allows (mu in [1/3, 2/3], nu in [0, 1])
//    are drawn again, i.e. the normal is truncated to the fit's prior. The spread of f over the draws holds
//    the non-linearity of the law and of the chronology (power laws of the constants, the turn between
//    regimes) and gives asymmetric intervals;
//  - linearised: var f = g^T C g with g the gradient of f in the coordinates above (central differences).
//    Correct to first order; the tests use it to check the sampling where the sigmas are small.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "craterkit/scaling/fit.hpp"
#include "craterkit/scaling/point_source.hpp"

namespace craterkit::scaling {

struct LawCovariance {
  ScalingLaw law;                         // the fitted (central) constants
  std::vector<std::string> names;         // constants with a covariance, in the order c1, c2, mu, nu
  Eigen::MatrixXd covariance;             // among names, natural units (c, not ln c)
  std::vector<std::string> fixed;         // held by the fit
  std::vector<std::string> undetermined;  // not determined by the fit's data; held at their values
  bool has_covariance() const { return !names.empty(); }
};

// The covariance of the law's constants in a fit (a fitted shared Y is left out: marginalised, since the
// chronology takes its cohesions from the user).
LawCovariance law_covariance(const FitResult& fit);

// The covariance in the coordinates of the draws (ln c1, ln c2, mu, nu; among names).
Eigen::MatrixXd internal_covariance(const LawCovariance& covariance);

struct LawSamples {
  std::vector<ScalingLaw> laws;
  int rejected = 0;  // draws outside the fit's ranges, drawn again
};

// `count` laws drawn from the multivariate normal of the free constants (held ones at their values).
// Throws InputError when count < 1, or when fewer than 1 in 100 draws fall inside the fit's ranges.
LawSamples sample_laws(const LawCovariance& covariance, int count, std::uint64_t seed);

// First-order variance of f at the central law: g^T C g, g by central differences of step 1e-3 sigma in
// the coordinates above. Zero without a covariance.
double linearised_variance(const LawCovariance& covariance,
                           const std::function<double(const ScalingLaw&)>& f);

// The 15.87, 50 and 84.13 percentiles (the 1-sigma range of a normal, as the model age reports), with
// linear interpolation between order statistics.
struct Percentiles {
  double p16 = 0.0;
  double p50 = 0.0;
  double p84 = 0.0;
};
Percentiles percentiles(std::vector<double> values);

}  // namespace craterkit::scaling
