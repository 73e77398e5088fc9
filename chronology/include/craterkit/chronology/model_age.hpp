#pragma once
// Model (crater-retention) ages from crater counts (docs/physics.md sec. 7), following the Poisson-likelihood
// approach of Michael et al. (2016, Icarus 277, 279): the craters in a diameter range are a Poisson
// process whose expected cumulative density after t years is N(>D, t) = t r(D) (or its equilibrium-capped
// form, conventions.hpp), r the production rate per m^2 per year (production.hpp).
//
// Unbinned diameters D_i (weights f_i) in [D_min, D_max), area A:
//   ln L(t) = -A [N(>D_min, t) - N(>D_max, t)] + sum_i f_i ln( -A dN/dD (D_i, t) )
// Binned cumulative counts C_j at D_j: bin j holds n_j = C_j - C_{j+1} craters in [D_j, D_{j+1}), and
//   ln L(t) = sum_j [ n_j ln lambda_j(t) - lambda_j(t) ],  lambda_j = A [N(>D_j, t) - N(>D_{j+1}, t)].
// With a uniform prior on [0, max_age] the normalised likelihood is the age's probability density;
// without the cap and with unit weights it is the Gamma density t^k exp(-A dr t), dr = r(D_min) - r(D_max).
// The classical cumulative fit (least squares of log N(>D) over the range, error t/sqrt(N)) is reported
// alongside for comparison.
#include <functional>
#include <limits>
#include <vector>

#include "craterkit/chronology/conventions.hpp"
#include "craterkit/chronology/crater_counts.hpp"
#include "craterkit/chronology/production.hpp"

namespace craterkit::chronology {

struct AgeFitOptions {
  double min_diameter = 0.0;  // m; 0 = the smallest crater (or bin) of the count
  double max_diameter = std::numeric_limits<double>::infinity();  // m
  EquilibriumCap cap;
  double max_age = 4.567e9;  // years, upper end of the uniform prior (age of the Solar System)
  std::size_t grid_points = 2001;
  // Also the classical cumulative fit. It needs r(D) at every counted crater; the draws of the scaling
  // law's constants (law_propagation.hpp) use only the likelihood and leave it out.
  bool cumulative_fit = true;
  // How the fraction f_i of a crater (buffered counting) enters the Poisson likelihood of unbinned counts:
  // true, each crater counts f_i (craterkit's default); false, each crater in the fit range counts once,
  // whatever its fraction, as craterstats' Poisson fit does. The observed cumulative counts and the
  // cumulative fit use the fractions either way.
  bool weight_by_fraction = true;
  // A flux that changed with time: the expected density is N(>D, t) = clock(t) r(D), with r the present
  // production rate and clock(t) the age in years of present-day flux that makes as many craters as t years
  // of the real flux (increasing, clock(0) = 0; e.g. chronology_clock of a chronology_system.hpp system).
  // Empty: constant flux, clock(t) = t.
  std::function<double(double)> clock;
  // The prior on [0, max_age]: uniform in age (false), or uniform in crater density, i.e. proportional to
  // the flux d clock / dt (true; what craterstats uses). The same for a constant flux.
  bool prior_uniform_in_density = false;
};

struct AgeEstimate {
  double min_diameter = 0.0;         // m, range actually used
  double max_diameter = 0.0;         // m (infinity for no upper limit)
  double craters_in_range = 0.0;     // weighted count k
  double production_in_range = 0.0;  // r(D_min) - r(D_max), per m^2 per year
  // Poisson-likelihood age, years.
  double median = 0.0;
  double mode = 0.0;
  double sigma1_low = 0.0, sigma1_high = 0.0;  // 15.87 and 84.13 percentiles
  double sigma2_low = 0.0, sigma2_high = 0.0;  // 2.275 and 97.725 percentiles
  bool reaches_max_age = false;  // the density is not negligible at max_age (e.g. saturated counts)
  std::vector<double> age_grid;  // years
  std::vector<double> density;   // probability density per year on age_grid
  // Classical cumulative fit, years.
  double cumulative_fit_age = 0.0;
  double cumulative_fit_sigma = 0.0;
};

AgeEstimate fit_model_age(const CraterCounts& counts, const ProductionFunction& production,
                          const AgeFitOptions& options);

// Quantile q in (0, 1) of a density tabulated on an increasing grid (trapezoidal CDF, linear interpolation).
double density_quantile(const std::vector<double>& grid, const std::vector<double>& density, double q);

}  // namespace craterkit::chronology
