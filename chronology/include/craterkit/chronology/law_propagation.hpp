#pragma once
// The uncertainty of a fitted scaling law carried into the chronology (docs/chronology.md, "Scaling-law
// uncertainty"). One set of draws of the fitted constants (scaling/law_uncertainty.hpp) is pushed through
// every quantity, so that the quantities stay correlated as they are: the relative rate between two
// cohesions uses the same draw for both, since one fit gives one law for every cohesion.
//
// Model ages: for each draw the age density of the counts is computed as for the central law
// (model_age.hpp). Two things are reported:
//  - the law term: the 15.87/50/84.13 percentiles, over the draws, of each draw's median age;
//  - the total: the age density averaged over the draws, i.e. the posterior of the age marginalised over
//    the constants (counting and law together), as median and 1- and 2-sigma bounds. Its quantiles are
//    taken from the pooled quantiles of every draw's density at the probabilities (j + 1/2)/M, j < M = 1000
//    (a stratified sample of the mixture: its CDF is exact to 1/(2M) in probability).
// The counting (Poisson) uncertainty is the central law's own age density (model_age.hpp).
#include <vector>

#include "craterkit/chronology/crater_counts.hpp"
#include "craterkit/chronology/model_age.hpp"
#include "craterkit/chronology/production.hpp"
#include "craterkit/scaling/law_uncertainty.hpp"
#include "craterkit/scaling/point_source.hpp"

namespace craterkit::chronology {

struct RateSpread {
  scaling::Percentiles impactor_radius;  // a(D) at the (weighted) mean speed of the set-up, m
  scaling::Percentiles rate;             // r(D), craters larger than D per m^2 per year
  scaling::Percentiles relative_rate;    // r(D; target) / r(D; reference), the same draw in both
};

// Over the draws `laws`, with the cohesion (strength) of `target` and of `reference`.
RateSpread rate_spread(const ProductionSetup& setup, const std::vector<scaling::ScalingLaw>& laws,
                       const scaling::Target& target, const scaling::Target& reference,
                       double impactor_density, double rim_diameter);

struct AgeSpread {
  scaling::Percentiles median;  // law term: the draws' median ages, years
  // Total (counting and law): the age density averaged over the draws, years.
  double total_median = 0.0;
  double total_sigma1_low = 0.0, total_sigma1_high = 0.0;  // 15.87 and 84.13 percentiles
  double total_sigma2_low = 0.0, total_sigma2_high = 0.0;  // 2.275 and 97.725 percentiles
};

// Over the draws `laws` (at least one), with options as for the central age (the cumulative fit is left
// out of the draws).
AgeSpread model_age_spread(const CraterCounts& counts, const ProductionSetup& setup,
                           const std::vector<scaling::ScalingLaw>& laws, const scaling::Target& target,
                           double impactor_density, const AgeFitOptions& options);

}  // namespace craterkit::chronology
