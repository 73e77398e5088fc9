#pragma once
// Ceres fit of the point-source law (docs/physics.md section 6) to a table of impacts and crater radii.
//
// Model: ln R_model(row; K1, K2 | H1, H2, mu, nu, [Y]) from the law in the chosen form.
// Residual of row i: (ln R_model - ln R_i) / s_i with s_i = sigma_i / R_i when the table gives
// crater_radius_sigma (chi^2 then has its usual meaning) and s_i = 1 otherwise (the covariance is then
// scaled by chi^2/dof, i.e. the scatter of the data sets the error bars; FitResult::weighted says which).
//
// Internally the coefficients (and Y) are fitted as logarithms, which keeps them positive and makes the
// problem well scaled; mu is bounded to [1/3, 2/3] and nu to [0, 1]. The fit is run from several starting
// points (a fixed, seeded spread over the allowed ranges) and the lowest cost is kept, so that a local
// minimum is not reported; the number of starts that reached that minimum is reported too.
//
// Uncertainties: 1-sigma from ceres::Covariance at the minimum (first-order, transformed from the log
// parameters by sigma_c = c sigma_ln c), and the correlation matrix of the free parameters.
// A parameter the data cannot determine is reported with determined = false and sigma = +infinity, and
// the covariance of the others is computed with it held at its fitted value (conditional). "Cannot
// determine" means either
//  - the Jacobian is (numerically) blind to it: it is the strongest component of a direction with a
//    singular value below 1e-7 of the largest (columns scaled to unit length), e.g. nu when every row has
//    the same density ratio; or
//  - its profile is flat on one side: holding it 4 natural scales away from the minimum (a factor e^4 for
//    a coefficient or Y, the bound for mu, 2 (i.e. the bound) for nu) and re-optimising the others raises
//    chi^2 by less than 4 (two sigma), e.g. K2 when every row is gravity-dominated (only an upper limit).
// A parameter at a bound is flagged at_bound (its sigma is then not meaningful).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "craterkit/scaling/point_source.hpp"
#include "craterkit/scaling/radii_table.hpp"

namespace craterkit::scaling {

// Where a fit is: stage "start", "profile" or "covariance", the number of that stage being worked on
// (0-based) of how many, and the solver's iteration in it (0 before the first).
struct FitProgress {
  std::string stage;
  int index = 0;
  int count = 0;
  int iteration = 0;
};

struct FitOptions {
  Form form = Form::holsapple;
  // Parameters held fixed, by name (K1, K2 or H1, H2, mu, nu, Y); other names are InputErrors.
  std::vector<std::pair<std::string, double>> fixed;
  // Fit one strength Y shared by all rows instead of each row's own strength column.
  bool shared_strength = false;
  int starts = 12;            // number of starting points (>= 1)
  unsigned int seed = 20221;  // seed of the starting-point spread (results are reproducible)
  // Keep every row's residual in FitResult::residuals (one FitResidual, 40 bytes, per row); without it only
  // FitResult::residual_summary is filled, which is what `craterkit fit` needs unless --residuals is given.
  bool keep_residuals = true;
  // Called at each solve (every start, every profile), after each of its iterations, and at the covariance,
  // for a progress line on large tables (a solve over millions of rows takes minutes).
  std::function<void(const FitProgress&)> progress;
};

struct FittedParameter {
  std::string name;  // K1, K2, H1, H2, mu, nu, Y
  double value = 0.0;
  double sigma = 0.0;  // 1-sigma; 0 for fixed, +inf for undetermined
  bool fixed = false;
  bool determined = true;
  bool at_bound = false;
};

struct FitResidual {
  int line = 0;               // line in the input table
  double observed = 0.0;      // R, m
  double model = 0.0;         // R from the fitted law, m
  double log_residual = 0.0;  // ln R_model - ln R
  double normalized = 0.0;    // log_residual / s_i
};

// Summary statistics of the residuals at the minimum, over every fitted row: what the fit JSON holds
// instead of one entry per row (a table of millions of rows gave a JSON of hundreds of megabytes).
struct ResidualSummary {
  std::size_t rows = 0;
  double mean_log_residual = 0.0;  // mean of ln R_model - ln R
  double rms_log_residual = 0.0;   // root mean square of ln R_model - ln R
  double rms_normalized = 0.0;     // sqrt(chi2 / rows)
  // Quantiles of ln R_model - ln R: smallest, 5 %, median, 95 %, largest (nearest rank).
  double log_residual_min = 0.0, log_residual_p05 = 0.0, log_residual_median = 0.0, log_residual_p95 = 0.0,
         log_residual_max = 0.0;
  // The row with the largest |normalized residual|: its table line and residuals.
  int largest_line = 0;
  double largest_log_residual = 0.0;
  double largest_normalized = 0.0;
};

struct FitResult {
  Form form = Form::holsapple;
  bool shared_strength = false;
  std::vector<FittedParameter> parameters;     // order: c1, c2, mu, nu, [Y]
  std::vector<std::string> correlation_names;  // free, determined parameters, in the order above
  Eigen::MatrixXd correlation;                 // among correlation_names
  Eigen::MatrixXd covariance;                  // among correlation_names (natural units)
  double chi2 = 0.0;
  int dof = 0;
  bool weighted = false;     // rows weighted by crater_radius_sigma
  double sigma_scale = 1.0;  // factor applied to the covariance (chi2/dof when unweighted)
  int starts = 0;
  int starts_at_minimum = 0;  // starts that converged to the reported minimum (cost within 1e-6)
  ResidualSummary residual_summary;
  std::vector<FitResidual> residuals;  // one per fitted row, in table order (FitOptions::keep_residuals)

  const FittedParameter& parameter(const std::string& name) const;  // throws std::out_of_range
  ScalingLaw law() const;                                           // fitted law (in `form`)
  std::optional<double> strength() const;                           // Y if fitted
};

// Throws InputError for unknown or duplicated fixed names, a table with fewer rows than free parameters,
// or shared_strength with a fixed Y that is not > 0 and finite.
FitResult fit_scaling_law(const RadiiTable& table, const FitOptions& options);
// The same over the rows of `table` at the given indices (in that order): a group of a table, fitted
// without copying its rows.
FitResult fit_scaling_law(const RadiiTable& table, std::span<const std::uint32_t> rows,
                          const FitOptions& options);

// The number of parameters fit_scaling_law would fit (c1, c2, mu, nu and a shared Y, less the fixed ones),
// after the same checks of the options (InputError for an unknown, repeated or out-of-range fixed name).
// A table needs more rows than this.
int free_parameter_count(const FitOptions& options);

}  // namespace craterkit::scaling
