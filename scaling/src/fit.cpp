// Ceres fit of the point-source law to a table of impacts and crater radii (see fit.hpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <ceres/ceres.h>

#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/fit.hpp"
#include "point_source_formula.hpp"

namespace craterkit::scaling {
namespace {

// Internal parameter vector: ln c1, ln c2, mu, nu, ln Y (Y only used with a shared strength).
constexpr int kC1 = 0;
constexpr int kC2 = 1;
constexpr int kMu = 2;
constexpr int kNu = 3;
constexpr int kY = 4;
constexpr int kParameterCount = 5;
constexpr double kMuLower = 1.0 / 3.0;
constexpr double kMuUpper = 2.0 / 3.0;
constexpr double kNuLower = 0.0;
constexpr double kNuUpper = 1.0;

bool is_log_parameter(int index) {
  return index == kC1 || index == kC2 || index == kY;
}

// One row's data in the form the residual needs (64 bytes: the flags together at the end).
struct RowTerms {
  double ln_pi2 = 0.0;
  double ln_pi3 = 0.0;     // of the row's own strength
  double ln_rho_u2 = 0.0;  // ln(rho U^2), to form pi3 from a shared Y
  double ln_pi4 = 0.0;
  double ln_length = 0.0;    // ln (m/rho)^(1/3)
  double ln_observed = 0.0;  // ln R
  double inverse_sigma = 1.0;
  bool has_gravity = false;
  bool has_strength = false;
};

// The rows a fit works on: every row of a table, or those at the given indices (a group).
class RowSelection {
 public:
  explicit RowSelection(const RadiiTable& table) : table_(table), all_(true) {}
  RowSelection(const RadiiTable& table, std::span<const std::uint32_t> indices)
      : table_(table), indices_(indices), all_(false) {}
  [[nodiscard]] std::size_t size() const { return all_ ? table_.rows.size() : indices_.size(); }
  [[nodiscard]] const ImpactRecord& operator[](std::size_t k) const {
    return table_.rows[all_ ? k : indices_[k]];
  }
  [[nodiscard]] const RadiiTable& table() const { return table_; }

 private:
  const RadiiTable& table_;
  std::span<const std::uint32_t> indices_;
  bool all_;
};

RowTerms row_terms(const ImpactRecord& row, bool weighted) {
  RowTerms t;
  const PiGroups pi = pi_groups(row.impactor, row.target);
  t.has_gravity = pi.pi2 > 0.0;
  t.ln_pi2 = t.has_gravity ? std::log(pi.pi2) : 0.0;
  t.has_strength = pi.pi3 > 0.0;
  t.ln_pi3 = t.has_strength ? std::log(pi.pi3) : 0.0;
  t.ln_rho_u2 = std::log(row.target.density * row.impactor.velocity * row.impactor.velocity);
  t.ln_pi4 = std::log(pi.pi4);
  t.ln_length = std::log(impactor_mass(row.impactor) / row.target.density) / 3.0;
  t.ln_observed = std::log(row.crater_radius);
  if (weighted) t.inverse_sigma = row.crater_radius / *row.crater_radius_sigma;  // 1 / (sigma_R / R)
  return t;
}

// The normalised residual of one row, (ln R_model - ln R) / s, for T = double or ceres::Jet.
template <typename T>
T row_residual(const RowTerms& terms, Form form, bool shared_strength, const T* p) {
  detail::LogPiGroups<T> pi;
  pi.ln_pi2 = T(terms.ln_pi2);
  pi.has_gravity = terms.has_gravity;
  pi.ln_pi4 = T(terms.ln_pi4);
  if (shared_strength) {
    pi.ln_pi3 = p[kY] - terms.ln_rho_u2;
    pi.has_strength = true;
  } else {
    pi.ln_pi3 = T(terms.ln_pi3);
    pi.has_strength = terms.has_strength;
  }
  const T ln_pi_r = detail::log_pi_R(form, p[kC1], p[kC2], p[kMu], p[kNu], pi);
  return (ln_pi_r + terms.ln_length - terms.ln_observed) * terms.inverse_sigma;
}

using Jet = ceres::Jet<double, 5>;

// Every parameter as a Jet seeded with its own derivative direction.
std::array<Jet, 5> seeded(const double* const* parameters) {
  std::array<Jet, 5> p;
  for (int i = 0; i < 5; ++i) p[static_cast<std::size_t>(i)] = Jet(parameters[i][0], i);
  return p;
}

// Every row's residual as ONE residual block of as many residuals as rows, over the five parameter blocks
// (ln c1, ln c2, mu, nu, ln Y) of size 1. One block per row made Ceres hold a cost function, a functor with
// the row's terms and the block's bookkeeping for every row (about 0.3 kB a row, 1.2 GB for 4 million rows,
// in every problem built); this block reads the rows where they are. The derivatives are those Ceres's
// automatic differentiation computed per row (forward mode, ceres::Jet over the same template).
class AllRowsResidual final : public ceres::CostFunction {
 public:
  AllRowsResidual(const std::vector<RowTerms>& rows, Form form, bool shared_strength)
      : rows_(rows), form_(form), shared_strength_(shared_strength) {
    set_num_residuals(static_cast<int>(rows.size()));
    for (int i = 0; i < kParameterCount; ++i) mutable_parameter_block_sizes()->push_back(1);
  }

  bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
    const std::size_t n = rows_.size();
    if (jacobians == nullptr) {
      std::array<double, kParameterCount> p{};
      for (int i = 0; i < kParameterCount; ++i) p[static_cast<std::size_t>(i)] = parameters[i][0];
      for (std::size_t k = 0; k < n; ++k)
        residuals[k] = row_residual(rows_[k], form_, shared_strength_, p.data());
      return true;
    }
    const std::array<Jet, 5> p = seeded(parameters);
    for (std::size_t k = 0; k < n; ++k) {
      const Jet r = row_residual(rows_[k], form_, shared_strength_, p.data());
      residuals[k] = r.a;
      for (int i = 0; i < kParameterCount; ++i) {
        if (jacobians[i] != nullptr) jacobians[i][k] = r.v[i];  // null for a constant block
      }
    }
    return true;
  }

 private:
  const std::vector<RowTerms>& rows_;
  Form form_;
  bool shared_strength_;
};

std::array<std::string, kParameterCount> parameter_names(Form form) {
  return {coefficient_name(form, 1), coefficient_name(form, 2), "mu", "nu", "Y"};
}

// Builds the problem over `values` (internal parametrisation); fixed flags make blocks constant.
void build_problem(ceres::Problem& problem, const std::vector<RowTerms>& rows, const FitOptions& options,
                   std::array<double, kParameterCount>& values,
                   const std::array<bool, kParameterCount>& held) {
  for (int i = 0; i < kParameterCount; ++i) problem.AddParameterBlock(&values[i], 1);
  problem.AddResidualBlock(new AllRowsResidual(rows, options.form, options.shared_strength), nullptr,
                           &values[kC1], &values[kC2], &values[kMu], &values[kNu], &values[kY]);
  for (int i = 0; i < kParameterCount; ++i) {
    if (held[i]) problem.SetParameterBlockConstant(&values[i]);
  }
  if (!held[kMu]) {
    problem.SetParameterLowerBound(&values[kMu], 0, kMuLower);
    problem.SetParameterUpperBound(&values[kMu], 0, kMuUpper);
  }
  if (!held[kNu]) {
    problem.SetParameterLowerBound(&values[kNu], 0, kNuLower);
    problem.SetParameterUpperBound(&values[kNu], 0, kNuUpper);
  }
}

double clamp_start(int index, double value) {
  if (index == kMu) return std::clamp(value, kMuLower, kMuUpper);
  if (index == kNu) return std::clamp(value, kNuLower, kNuUpper);
  return value;
}

// Starting points: the first at typical published values, the rest spread uniformly (seeded) over
// plausible ranges; fixed parameters keep their values.
std::vector<std::array<double, kParameterCount>> starting_points(
    const FitOptions& options, const std::array<double, kParameterCount>& base,
    const std::array<bool, kParameterCount>& fixed, double ln_y_typical) {
  std::mt19937_64 random(options.seed);
  const bool holsapple = options.form == Form::holsapple;
  // ranges of the internal parameters
  const std::array<std::pair<double, double>, kParameterCount> range{{
      {std::log(0.05), std::log(5.0)},
      holsapple ? std::pair{std::log(1e-3), std::log(1e3)} : std::pair{std::log(0.05), std::log(5.0)},
      {0.35, 0.65},
      {0.2, 0.6},
      {ln_y_typical - 5.0, ln_y_typical + 5.0},
  }};
  std::vector<std::array<double, kParameterCount>> points;
  std::array<double, kParameterCount> typical = base;
  const std::array<double, kParameterCount> defaults{
      std::log(holsapple ? 1.0 : 0.6), std::log(holsapple ? 1.0 : 0.5), 0.45, 0.4, ln_y_typical};
  for (int i = 0; i < kParameterCount; ++i) {
    if (!fixed[i]) typical[i] = defaults[i];
  }
  points.push_back(typical);
  while (static_cast<int>(points.size()) < options.starts) {
    std::array<double, kParameterCount> point = base;
    for (int i = 0; i < kParameterCount; ++i) {
      std::uniform_real_distribution<double> uniform(range[i].first, range[i].second);
      const double draw =
          uniform(random);  // drawn for every parameter so the spread does not depend on `fixed`
      if (!fixed[i]) point[i] = clamp_start(i, draw);
    }
    points.push_back(point);
  }
  return points;
}

// Natural scale of each internal parameter, for the profile test of determination.
double determination_scale(int index) {
  if (index == kMu) return (kMuUpper - kMuLower) / 2.0;
  if (index == kNu) return 0.5;
  return 1.0;  // ln c: a factor e
}

// The R factor (k x k, upper triangular) of the Jacobian of every row's residual with respect to the
// parameters `columns` at `values`: Householder QR over blocks of rows, each block stacked under the R of
// the rows before it. J^T J = R^T R, so R has J's singular values and right singular vectors and gives its
// covariance, while only one block of rows is held at a time (a dense copy of the whole Jacobian, as
// ceres::Covariance makes, took gigabytes for millions of rows).
Eigen::MatrixXd jacobian_r_factor(const std::vector<RowTerms>& rows, const FitOptions& options,
                                  const std::array<double, kParameterCount>& values,
                                  const std::vector<int>& columns) {
  const auto k = static_cast<Eigen::Index>(columns.size());
  constexpr Eigen::Index block = 4096;
  Eigen::MatrixXd stacked(k + block, k);
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(k, k);
  std::array<const double*, kParameterCount> pointers{};
  for (int i = 0; i < kParameterCount; ++i)
    pointers[static_cast<std::size_t>(i)] = &values[static_cast<std::size_t>(i)];
  const std::array<Jet, 5> p = seeded(pointers.data());
  const auto n = static_cast<Eigen::Index>(rows.size());
  for (Eigen::Index first = 0; first < n; first += block) {
    const Eigen::Index count = std::min(block, n - first);
    stacked.topRows(k) = r;
    for (Eigen::Index j = 0; j < count; ++j) {
      const Jet residual = row_residual(rows[static_cast<std::size_t>(first + j)], options.form,
                                        options.shared_strength, p.data());
      for (Eigen::Index c = 0; c < k; ++c)
        stacked(k + j, c) = residual.v[columns[static_cast<std::size_t>(c)]];
    }
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(stacked.topRows(k + count));
    r = qr.matrixQR().topRows(k).triangularView<Eigen::Upper>();
  }
  return r;
}

// Indices among `free` (into the parameter vector) whose direction the Jacobian cannot resolve.
std::vector<int> null_space_parameters(const std::vector<RowTerms>& rows, const FitOptions& options,
                                       const std::array<double, kParameterCount>& values,
                                       const std::vector<int>& free) {
  Eigen::MatrixXd jacobian =
      jacobian_r_factor(rows, options, values, free);  // the R of J: same columns' norms
  std::vector<int> out;
  // Columns scaled to unit length, so that the test is about directions, not units.
  for (Eigen::Index c = 0; c < jacobian.cols(); ++c) {
    const double norm = jacobian.col(c).norm();
    if (!(norm > 0.0)) {
      out.push_back(free[static_cast<std::size_t>(c)]);
      jacobian.col(c).setZero();
    } else {
      jacobian.col(c) /= norm;
    }
  }
  if (!out.empty()) return out;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(jacobian, Eigen::ComputeFullV);
  const auto& singular = svd.singularValues();
  const double largest = singular.size() > 0 ? singular(0) : 0.0;
  // For each (near-)null direction, the parameter that moves most along it; the caller holds it and
  // looks again, so that a degeneracy among several parameters costs only one of them.
  std::set<int> flagged;
  for (Eigen::Index k = 0; k < singular.size(); ++k) {
    if (singular(k) > 1e-7 * largest) continue;
    Eigen::Index strongest = 0;
    svd.matrixV().col(k).cwiseAbs().maxCoeff(&strongest);
    flagged.insert(free[static_cast<std::size_t>(strongest)]);
  }
  return {flagged.begin(), flagged.end()};
}

// ---------------------------------------------------------------- the steps of fit_scaling_law

using Values = std::array<double, kParameterCount>;  // internal parametrisation
using Flags = std::array<bool, kParameterCount>;

// What the fit works on, once the options and the table have been checked.
struct FitSetup {
  std::array<std::string, kParameterCount> names;  // K1, K2 or H1, H2, then mu, nu, Y
  Flags fixed{};                                   // held at the user's value (--fix)
  Flags held{};                                    // fixed, or not in the model (Y without a shared strength)
  Values base{std::log(1.0), std::log(1.0), 0.45, 0.4, 0.0};  // the fixed ones at their given values
  std::vector<RowTerms> rows;
  bool weighted = false;  // the table gives crater_radius_sigma
  int free_count = 0;
  // Centre of the starting values of a shared Y: the rows' median strength, 1 Pa without strengths.
  double ln_y_typical = 0.0;
};

// The fixed parameters, by name: each a parameter of this form (Y only with a shared strength), fixed
// once, at a value the law allows; it then keeps that value in every solve.
void apply_fixed(const FitOptions& options, FitSetup& setup) {
  const auto& names = setup.names;
  for (const auto& [name, value] : options.fixed) {
    const auto it = std::find(names.begin(), names.end(), name);
    const bool y_allowed = options.shared_strength;
    if (it == names.end() || (name == "Y" && !y_allowed)) {
      throw InputError("cannot fix '" + name + "': allowed names for the " + to_string(options.form) +
                       " form are " + names[0] + ", " + names[1] + ", mu, nu" +
                       (y_allowed ? ", Y" : " (and Y with a shared strength)"));
    }
    const int index = static_cast<int>(it - names.begin());
    if (setup.fixed[index]) throw InputError("parameter '" + name + "' is fixed twice");
    const bool ok =
        std::isfinite(value) && (index == kNu ? value >= 0.0 : value > 0.0) && (index != kMu || value <= 1.0);
    if (!ok) {
      throw InputError("fixed " + name + " = " + std::to_string(value) + " is not allowed: must be " +
                       (index == kNu   ? "finite and >= 0"
                        : index == kMu ? "in (0, 1]"
                                       : "finite and > 0"));
    }
    setup.fixed[index] = true;
    setup.base[index] = is_log_parameter(index) ? std::log(value) : value;
  }
}

// The table's rows in the residual's form. A row needs gravity or a strength, else the law has no finite
// crater; the median of the rows' strengths centres the starting values of a shared Y.
void read_rows(const RowSelection& rows, const FitOptions& options, FitSetup& setup) {
  const RadiiTable& table = rows.table();
  setup.weighted = table.has_sigma();
  std::vector<double> strengths;
  setup.rows.reserve(rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const ImpactRecord& row = rows[k];
    const bool has_strength = options.shared_strength || row.target.strength > 0.0;
    if (!(row.target.gravity > 0.0) && !has_strength) {
      throw InputError(table.source + ":" + std::to_string(row.line) +
                       ": gravity and strength are both 0, for which the law has no finite crater");
    }
    if (row.target.strength > 0.0) strengths.push_back(row.target.strength);
    setup.rows.push_back(row_terms(row, setup.weighted));
  }
  if (!strengths.empty()) {
    std::nth_element(strengths.begin(), strengths.begin() + strengths.size() / 2, strengths.end());
    setup.ln_y_typical = std::log(strengths[strengths.size() / 2]);
  }
}

// Checks the options and the table and gathers what the fit works on: the number of starts, the fixed
// parameters, every row, then that something is free and that there are more rows than free parameters
// (so that chi^2/dof exists).
FitSetup prepare_fit(const RowSelection& rows, const FitOptions& options) {
  const RadiiTable& table = rows.table();
  FitSetup setup;
  setup.names = parameter_names(options.form);
  if (options.starts < 1) throw InputError("starts = " + std::to_string(options.starts) + ": must be >= 1");
  apply_fixed(options, setup);
  setup.held = setup.fixed;
  if (!options.shared_strength) setup.held[kY] = true;  // unused
  read_rows(rows, options, setup);
  for (int i = 0; i < kParameterCount; ++i) setup.free_count += setup.held[i] ? 0 : 1;
  if (setup.free_count == 0) throw InputError("every parameter is fixed: nothing to fit");
  if (static_cast<int>(setup.rows.size()) <= setup.free_count) {
    throw InputError(table.source + ": " + std::to_string(setup.rows.size()) + " rows for " +
                     std::to_string(setup.free_count) + " free parameters; at least " +
                     std::to_string(setup.free_count + 1) + " rows are required");
  }
  return setup;
}

// The solver for every solve of the fit (starts and profiles): dense QR for these few parameters,
// tolerances far below any scatter of real data so that a solve stops at the minimum and not short of
// it, silent, and on one thread so that the numbers do not depend on the machine's thread count.
ceres::Solver::Options solver_options() {
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_QR;
  options.max_num_iterations = 500;
  options.function_tolerance = 1e-15;
  options.gradient_tolerance = 1e-15;
  options.parameter_tolerance = 1e-14;
  options.logging_type = ceres::SILENT;
  options.num_threads = 1;
  return options;
}

// The lowest minimum found and how many starts reached it.
struct Minimum {
  Values values{};
  double cost = std::numeric_limits<double>::infinity();
  int starts_at_minimum = 0;  // within 1e-6 of the cost, relative
};

// Reports a solve's iterations to FitOptions::progress (reading only: the solve is unchanged).
class ProgressCallback final : public ceres::IterationCallback {
 public:
  ProgressCallback(const FitOptions& options, FitProgress where)
      : options_(options), where_(std::move(where)) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    where_.iteration = summary.iteration;
    options_.progress(where_);
    return ceres::SOLVER_CONTINUE;
  }

 private:
  const FitOptions& options_;
  FitProgress where_;
};

// ceres::Solve, reporting its stage and iterations when the options ask for progress.
void solve(const ceres::Solver::Options& solver, ceres::Problem& problem, ceres::Solver::Summary& summary,
           const FitOptions& options, const FitProgress& where) {
  if (!options.progress) {
    ceres::Solve(solver, &problem, &summary);
    return;
  }
  options.progress(where);
  ProgressCallback callback(options, where);
  ceres::Solver::Options reporting = solver;
  reporting.callbacks.push_back(&callback);
  ceres::Solve(reporting, &problem, &summary);
}

// Solves from every starting point and keeps the lowest cost: the law is non-linear in mu and nu, so a
// single local solve could report a local minimum. Starts whose solve fails are skipped; the number of
// starts that reached the minimum says how clearly it stands out.
Minimum multi_start(const FitSetup& setup, const FitOptions& options, const ceres::Solver::Options& solver) {
  Minimum best;
  std::vector<double> costs;
  int done = 0;
  for (auto start : starting_points(options, setup.base, setup.fixed, setup.ln_y_typical)) {
    ceres::Problem problem;
    build_problem(problem, setup.rows, options, start, setup.held);
    ceres::Solver::Summary summary;
    solve(solver, problem, summary, options, {"start", done++, options.starts, 0});
    if (!summary.IsSolutionUsable() || !std::isfinite(summary.final_cost)) continue;
    costs.push_back(summary.final_cost);
    if (summary.final_cost < best.cost) {
      best.cost = summary.final_cost;
      best.values = start;
    }
  }
  if (!std::isfinite(best.cost)) throw std::runtime_error("the scaling fit failed from every starting point");
  for (double cost : costs) {
    if (cost - best.cost <= 1e-6 * std::max(best.cost, 1e-12)) ++best.starts_at_minimum;
  }
  return best;
}

// The value at nearest rank q (0..1) of `values`, which it partly reorders.
double nearest_rank(std::vector<double>& values, double q) {
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
  const auto at =
      values.begin() + static_cast<std::ptrdiff_t>(std::clamp<std::size_t>(rank, 1, values.size()) - 1);
  std::nth_element(values.begin(), at, values.end());
  return *at;
}

// Each row's residual at the minimum (normalised, in ln R, and the model radius) and their summary, chi^2,
// the degrees of freedom, and the scale of the covariance: 1 when the table gives sigmas, else chi^2/dof (the
// scatter of the data then sets the error bars). The rows' residuals are kept only when asked for.
void add_residuals(const RowSelection& rows, const FitSetup& setup, const FitOptions& options,
                   const Values& values, FitResult& result) {
  double chi2 = 0.0, sum = 0.0, sum_squares = 0.0;
  std::vector<double> log_residuals(setup.rows.size());
  ResidualSummary& summary = result.residual_summary;
  if (options.keep_residuals) result.residuals.reserve(setup.rows.size());
  for (std::size_t i = 0; i < setup.rows.size(); ++i) {
    const double normalized =
        row_residual(setup.rows[i], options.form, options.shared_strength, values.data());
    FitResidual r;
    r.line = rows[i].line;
    r.observed = rows[i].crater_radius;
    r.normalized = normalized;
    r.log_residual = normalized / setup.rows[i].inverse_sigma;
    r.model = r.observed * std::exp(r.log_residual);
    if (options.keep_residuals) result.residuals.push_back(r);
    chi2 += normalized * normalized;
    sum += r.log_residual;
    sum_squares += r.log_residual * r.log_residual;
    log_residuals[i] = r.log_residual;
    if (i == 0 || std::abs(normalized) > std::abs(summary.largest_normalized)) {
      summary.largest_line = r.line;
      summary.largest_normalized = normalized;
      summary.largest_log_residual = r.log_residual;
    }
  }
  const auto n = static_cast<double>(setup.rows.size());
  summary.rows = setup.rows.size();
  summary.mean_log_residual = sum / n;
  summary.rms_log_residual = std::sqrt(sum_squares / n);
  summary.rms_normalized = std::sqrt(chi2 / n);
  summary.log_residual_min = *std::min_element(log_residuals.begin(), log_residuals.end());
  summary.log_residual_max = *std::max_element(log_residuals.begin(), log_residuals.end());
  summary.log_residual_p05 = nearest_rank(log_residuals, 0.05);
  summary.log_residual_median = nearest_rank(log_residuals, 0.5);
  summary.log_residual_p95 = nearest_rank(log_residuals, 0.95);
  result.chi2 = chi2;
  result.dof = static_cast<int>(setup.rows.size()) - setup.free_count;
  result.sigma_scale = setup.weighted ? 1.0 : chi2 / result.dof;
}

// The parameters still free: neither held nor found undetermined, in index order.
std::vector<int> free_parameters(const Flags& held, const std::vector<bool>& undetermined) {
  std::vector<int> out;
  for (int i = 0; i < kParameterCount; ++i) {
    if (!held[i] && !undetermined[i]) out.push_back(i);
  }
  return out;
}

// Determination, test 1 (rank): flags the parameters along directions the Jacobian at the minimum cannot
// see at all, one per direction and round, until the rest has full rank.
void flag_null_space(const FitSetup& setup, const FitOptions& options, const Values& values,
                     std::vector<bool>& undetermined) {
  for (int round = 0; round < kParameterCount; ++round) {
    const auto free = free_parameters(setup.held, undetermined);
    if (free.empty()) break;
    const auto flagged = null_space_parameters(setup.rows, options, values, free);
    if (flagged.empty()) break;
    for (int index : flagged) undetermined[index] = true;
  }
}

// Determination, test 2 (profile): chi^2 (others re-optimised) must rise by 4 (2 sigma) on both sides of
// the minimum within a window of 4 natural scales, clamped to the bounds: mu's window spans its whole range,
// so mu counts as determined only where the data exclude both 1/3 and 2/3 at 2 sigma (a 2-sigma interval
// that reaches a bound is set by the bound, not by the data). Only a side where the minimum sits on the
// bound is not tested.
bool profile_rises(int index, const FitSetup& setup, const FitOptions& options,
                   const ceres::Solver::Options& solver, const Values& values, double best_cost,
                   double sigma_scale, const std::vector<bool>& undetermined, const FitProgress& where) {
  const double window = 4.0 * determination_scale(index);
  for (const double sign : {-1.0, 1.0}) {
    Values trial = values;
    trial[index] = clamp_start(index, values[index] + sign * window);
    if (std::abs(trial[index] - values[index]) < 1e-9) continue;
    Flags trial_held = setup.held;
    trial_held[index] = true;
    for (int i = 0; i < kParameterCount; ++i) trial_held[i] = trial_held[i] || undetermined[i];
    ceres::Problem profile;
    build_problem(profile, setup.rows, options, trial, trial_held);
    ceres::Solver::Summary summary;
    solve(solver, profile, summary, options, where);
    const double delta_chi2 = 2.0 * (summary.final_cost - best_cost) / sigma_scale;
    if (!(delta_chi2 >= 4.0)) return false;
  }
  return true;
}

// Flags every free parameter whose profile does not rise on both sides; later profiles hold the ones
// flagged before them.
void flag_flat_profiles(const FitSetup& setup, const FitOptions& options,
                        const ceres::Solver::Options& solver, const Values& values, double best_cost,
                        double sigma_scale, std::vector<bool>& undetermined) {
  const auto free = free_parameters(setup.held, undetermined);
  int done = 0;
  for (int index : free) {
    const FitProgress where{"profile", done++, static_cast<int>(free.size()), 0};
    if (!profile_rises(index, setup, options, solver, values, best_cost, sigma_scale, undetermined, where)) {
      undetermined[index] = true;
    }
  }
}

// Determination, step 3: the covariance of the determined free parameters with the undetermined ones
// held at their values (a covariance conditional on them), scaled by sigma_scale: (J^T J)^-1 from the SVD
// of J (through its R factor, jacobian_r_factor()), as ceres::Covariance computes it with DENSE_SVD and
// null_space_rank 0 (a reciprocal condition number below 1e-14, i.e. a singular-value ratio below 1e-7, is
// numerically singular), without its dense copies of the whole Jacobian. Where it is singular although the
// tests above passed, the last free parameter is given up in turn.
Eigen::MatrixXd conditional_covariance(const FitSetup& setup, const FitOptions& options, const Values& values,
                                       std::vector<bool>& undetermined, double sigma_scale) {
  constexpr double min_singular_value_ratio = 1e-7;  // sqrt of Ceres's min_reciprocal_condition_number
  Eigen::MatrixXd internal_covariance;
  for (int round = 0; round < kParameterCount; ++round) {
    const auto free = free_parameters(setup.held, undetermined);
    if (free.empty()) break;
    const Eigen::MatrixXd r = jacobian_r_factor(setup.rows, options, values, free);
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(r, Eigen::ComputeFullV);
    const Eigen::VectorXd& singular = svd.singularValues();
    if (singular.size() > 0 && singular(0) > 0.0 &&
        singular(singular.size() - 1) / singular(0) >= min_singular_value_ratio) {
      const Eigen::VectorXd inverse_squares = singular.array().square().inverse();
      internal_covariance = svd.matrixV() * inverse_squares.asDiagonal() * svd.matrixV().transpose();
      internal_covariance *= sigma_scale;
      break;
    }
    undetermined[static_cast<std::size_t>(free.back())] = true;
  }
  return internal_covariance;
}

// The parameters in natural units: c = e^(ln c) for the coefficients and Y.
Values natural_values(const Values& values) {
  Values natural{};
  for (int i = 0; i < kParameterCount; ++i)
    natural[i] = is_log_parameter(i) ? std::exp(values[i]) : values[i];
  return natural;
}

// One entry per parameter of the model (Y only with a shared strength): its value and what the fit knows
// of it. sigma is 0 when fixed and infinite until the covariance gives one; at_bound marks mu or nu on a
// bound of its range, where sigma means little.
void add_parameters(const FitSetup& setup, const FitOptions& options, const Values& natural,
                    const std::vector<bool>& undetermined, FitResult& result) {
  const int parameter_count = options.shared_strength ? kParameterCount : kParameterCount - 1;
  for (int i = 0; i < parameter_count; ++i) {
    FittedParameter p;
    p.name = setup.names[i];
    p.value = natural[i];
    p.fixed = setup.fixed[i];
    p.determined = !undetermined[i];
    p.sigma = p.fixed ? 0.0 : std::numeric_limits<double>::infinity();
    if (i == kMu) p.at_bound = !p.fixed && (p.value - kMuLower < 1e-6 || kMuUpper - p.value < 1e-6);
    if (i == kNu) p.at_bound = !p.fixed && (p.value - kNuLower < 1e-6 || kNuUpper - p.value < 1e-6);
    result.parameters.push_back(p);
  }
}

// The covariance and correlation of the free parameters in natural units, to first order
// (sigma_c = c sigma_ln c), and their sigmas; nothing when the covariance could not be computed.
void add_covariance(const FitSetup& setup, const std::vector<int>& free, const Values& natural,
                    const Eigen::MatrixXd& internal_covariance, FitResult& result) {
  const auto n = static_cast<Eigen::Index>(free.size());
  if (internal_covariance.rows() != n || n == 0) return;
  Eigen::VectorXd jacobian(n);
  for (Eigen::Index k = 0; k < n; ++k) jacobian(k) = is_log_parameter(free[k]) ? natural[free[k]] : 1.0;
  result.covariance = jacobian.asDiagonal() * internal_covariance * jacobian.asDiagonal();
  result.correlation.resize(n, n);
  for (Eigen::Index r = 0; r < n; ++r) {
    for (Eigen::Index c = 0; c < n; ++c) {
      result.correlation(r, c) =
          result.covariance(r, c) / std::sqrt(result.covariance(r, r) * result.covariance(c, c));
    }
  }
  for (Eigen::Index k = 0; k < n; ++k) {
    result.correlation_names.push_back(setup.names[free[k]]);
    result.parameters[free[k]].sigma = std::sqrt(result.covariance(k, k));
  }
}

}  // namespace

const FittedParameter& FitResult::parameter(const std::string& name) const {
  for (const auto& p : parameters) {
    if (p.name == name) return p;
  }
  throw std::out_of_range("fit has no parameter '" + name + "'");
}

ScalingLaw FitResult::law() const {
  ScalingLaw law;
  law.form = form;
  law.coefficient_1 = parameters.at(kC1).value;
  law.coefficient_2 = parameters.at(kC2).value;
  law.mu = parameters.at(kMu).value;
  law.nu = parameters.at(kNu).value;
  return law;
}

std::optional<double> FitResult::strength() const {
  if (!shared_strength) return std::nullopt;
  return parameters.at(kY).value;
}

int free_parameter_count(const FitOptions& options) {
  FitSetup setup;
  setup.names = parameter_names(options.form);
  apply_fixed(options, setup);
  int count = 0;
  for (int i = 0; i < kParameterCount; ++i) {
    const bool in_model = i != kY || options.shared_strength;
    count += in_model && !setup.fixed[i] ? 1 : 0;
  }
  return count;
}

namespace {

FitResult fit_rows(const RowSelection& rows, const FitOptions& options) {
  const FitSetup setup = prepare_fit(rows, options);
  const ceres::Solver::Options solver = solver_options();
  FitResult result;
  result.form = options.form;
  result.shared_strength = options.shared_strength;
  result.weighted = setup.weighted;
  result.starts = options.starts;
  const Minimum minimum = multi_start(setup, options, solver);
  result.starts_at_minimum = minimum.starts_at_minimum;

  // The Jacobian and covariance at the minimum say which parameters the data determine (see fit.hpp) and
  // how well.
  const Values values = minimum.values;
  add_residuals(rows, setup, options, values, result);
  std::vector<bool> undetermined(kParameterCount, false);
  flag_null_space(setup, options, values, undetermined);
  flag_flat_profiles(setup, options, solver, values, minimum.cost, result.sigma_scale, undetermined);
  if (options.progress) options.progress({"covariance", 0, 1, 0});
  const Eigen::MatrixXd internal_covariance =
      conditional_covariance(setup, options, values, undetermined, result.sigma_scale);

  const Values natural = natural_values(values);
  add_parameters(setup, options, natural, undetermined, result);
  add_covariance(setup, free_parameters(setup.held, undetermined), natural, internal_covariance, result);
  return result;
}

}  // namespace

FitResult fit_scaling_law(const RadiiTable& table, const FitOptions& options) {
  return fit_rows(RowSelection(table), options);
}

FitResult fit_scaling_law(const RadiiTable& table, std::span<const std::uint32_t> rows,
                          const FitOptions& options) {
  return fit_rows(RowSelection(table, rows), options);
}

}  // namespace craterkit::scaling
