#pragma once
// Relative crater-formation rates between two cohesions or two scaling laws, as a function of crater
// size (docs/physics.md sec. 7): the ratio of production rates r_B(D) / r_A(D). Everything that does not
// depend on the scaling law (P_i, area, normalisation) cancels.
//
// Closed forms for a single power law dN/da ∝ a^q with the target-only cross-section at one speed:
//   ratio = (a_B / a_A)^(q+1)                         (any law: only the impactor sizes matter)
//   pure strength regime:  a ∝ D Y^(mu/2)   =>  ratio = (Y_B / Y_A)^((q+1) mu / 2)
//   pure gravity regime:   a ∝ D^((2+mu)/2) H1^(-(2+mu)/2)  =>  ratio = (H1_B / H1_A)^(-(q+1)(2+mu)/2)
// e.g. D/d = 100 instead of 10 with q = -4 gives (1/10)^(-3) = 10^3 times more craters of a given size.
#include "craterkit/chronology/production.hpp"

namespace craterkit::chronology {

struct RelativeRate {
  double rim_diameter = 0.0;       // D, m
  double impactor_radius_a = 0.0;  // a_A(D) at the first speed of the distribution, m
  double impactor_radius_b = 0.0;  // a_B(D), m
  double rate_a = 0.0;             // r_A(D), per m^2 per year
  double rate_b = 0.0;             // r_B(D)
  double ratio = 0.0;              // r_B / r_A
};

RelativeRate relative_rate(const ProductionSetup& setup, const ImpactorRadiusFunction& law_a,
                           const ImpactorRadiusFunction& law_b, double rim_diameter);

}  // namespace craterkit::chronology
