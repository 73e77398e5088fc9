// Covariance of a fitted law, its seeded draws and first-order propagation (see law_uncertainty.hpp).
#include "craterkit/scaling/law_uncertainty.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "craterkit/common/input_error.hpp"

namespace craterkit::scaling {
namespace {

// The ranges the fit allows (fit.hpp): draws outside them are drawn again.
constexpr double kMuLower = 1.0 / 3.0;
constexpr double kMuUpper = 2.0 / 3.0;
constexpr double kNuLower = 0.0;
constexpr double kNuUpper = 1.0;

// Index of a constant in (c1, c2, mu, nu).
int constant_index(Form form, const std::string& name) {
  if (name == coefficient_name(form, 1)) return 0;
  if (name == coefficient_name(form, 2)) return 1;
  if (name == "mu") return 2;
  if (name == "nu") return 3;
  return -1;
}

double& constant(ScalingLaw& law, int index) {
  switch (index) {
    case 0:
      return law.coefficient_1;
    case 1:
      return law.coefficient_2;
    case 2:
      return law.mu;
    default:
      return law.nu;
  }
}

bool is_coefficient(int index) {
  return index < 2;
}

// Jacobian of (natural -> internal) per constant: 1/c for a coefficient (ln c), 1 for an exponent.
Eigen::VectorXd internal_scale(const LawCovariance& c) {
  Eigen::VectorXd scale(static_cast<Eigen::Index>(c.names.size()));
  ScalingLaw law = c.law;
  for (std::size_t k = 0; k < c.names.size(); ++k) {
    const int index = constant_index(law.form, c.names[k]);
    scale(static_cast<Eigen::Index>(k)) = is_coefficient(index) ? 1.0 / constant(law, index) : 1.0;
  }
  return scale;
}

// The law at internal coordinates x (among names) around the central law.
ScalingLaw law_at(const LawCovariance& c, const Eigen::VectorXd& x) {
  ScalingLaw law = c.law;
  for (std::size_t k = 0; k < c.names.size(); ++k) {
    const int index = constant_index(law.form, c.names[k]);
    const double value = x(static_cast<Eigen::Index>(k));
    constant(law, index) = is_coefficient(index) ? std::exp(value) : value;
  }
  return law;
}

Eigen::VectorXd central(const LawCovariance& c) {
  Eigen::VectorXd x(static_cast<Eigen::Index>(c.names.size()));
  ScalingLaw law = c.law;
  for (std::size_t k = 0; k < c.names.size(); ++k) {
    const int index = constant_index(law.form, c.names[k]);
    x(static_cast<Eigen::Index>(k)) =
        is_coefficient(index) ? std::log(constant(law, index)) : constant(law, index);
  }
  return x;
}

bool inside_fit_ranges(const LawCovariance& c, const ScalingLaw& law) {
  for (const auto& name : c.names) {
    if (name == "mu" && !(law.mu >= kMuLower && law.mu <= kMuUpper)) return false;
    if (name == "nu" && !(law.nu >= kNuLower && law.nu <= kNuUpper)) return false;
  }
  return true;
}

// A standard normal from a Mersenne Twister by Box-Muller: both are specified exactly, so the draws do not
// depend on the standard library (std::normal_distribution does).
class StandardNormal {
 public:
  explicit StandardNormal(std::uint64_t seed) : random_(seed) {}
  double operator()() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = (static_cast<double>(random_() >> 11) + 1.0) * 0x1.0p-53;  // (0, 1]
    const double u2 = static_cast<double>(random_() >> 11) * 0x1.0p-53;          // [0, 1)
    const double radius = std::sqrt(-2.0 * std::log(u1));
    spare_ = radius * std::sin(2.0 * std::numbers::pi * u2);
    has_spare_ = true;
    return radius * std::cos(2.0 * std::numbers::pi * u2);
  }

 private:
  std::mt19937_64 random_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace

LawCovariance law_covariance(const FitResult& fit) {
  LawCovariance out;
  out.law = fit.law();
  std::vector<Eigen::Index> keep;
  for (std::size_t k = 0; k < fit.correlation_names.size(); ++k) {
    if (constant_index(fit.form, fit.correlation_names[k]) < 0) continue;  // Y
    keep.push_back(static_cast<Eigen::Index>(k));
    out.names.push_back(fit.correlation_names[k]);
  }
  const auto n = static_cast<Eigen::Index>(keep.size());
  out.covariance.resize(n, n);
  for (Eigen::Index r = 0; r < n; ++r) {
    for (Eigen::Index c = 0; c < n; ++c) out.covariance(r, c) = fit.covariance(keep[r], keep[c]);
  }
  for (const auto& p : fit.parameters) {
    if (constant_index(fit.form, p.name) < 0) continue;
    if (p.fixed) out.fixed.push_back(p.name);
    if (!p.determined) out.undetermined.push_back(p.name);
  }
  return out;
}

Eigen::MatrixXd internal_covariance(const LawCovariance& c) {
  const Eigen::VectorXd scale = internal_scale(c);
  return scale.asDiagonal() * c.covariance * scale.asDiagonal();
}

LawSamples sample_laws(const LawCovariance& c, int count, std::uint64_t seed) {
  if (count < 1) throw InputError("number of law samples " + std::to_string(count) + " must be >= 1");
  LawSamples out;
  out.laws.reserve(static_cast<std::size_t>(count));
  if (!c.has_covariance()) {
    out.laws.assign(static_cast<std::size_t>(count), c.law);
    return out;
  }
  // C = V diag(lambda) V^T, x = x0 + V diag(sqrt(lambda)) z: valid for a covariance that is only
  // semi-definite (a tiny negative eigenvalue from rounding counts as zero).
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(internal_covariance(c));
  const Eigen::MatrixXd factor =
      eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt().asDiagonal();
  const Eigen::VectorXd x0 = central(c);
  StandardNormal normal(seed);
  const long long max_draws = 100LL * count;
  Eigen::VectorXd z(x0.size());
  for (long long draw = 0; draw < max_draws && static_cast<int>(out.laws.size()) < count; ++draw) {
    for (Eigen::Index k = 0; k < z.size(); ++k) z(k) = normal();
    const ScalingLaw law = law_at(c, x0 + factor * z);
    if (inside_fit_ranges(c, law)) {
      out.laws.push_back(law);
    } else {
      ++out.rejected;
    }
  }
  if (static_cast<int>(out.laws.size()) < count) {
    throw InputError(
        "the distribution of the fitted constants lies mostly outside the ranges the fit allows "
        "(mu in [1/3, 2/3], nu in [0, 1]): fewer than 1 in 100 draws fall inside");
  }
  return out;
}

double linearised_variance(const LawCovariance& c, const std::function<double(const ScalingLaw&)>& f) {
  if (!c.has_covariance()) return 0.0;
  const Eigen::MatrixXd cov = internal_covariance(c);
  const Eigen::VectorXd x0 = central(c);
  Eigen::VectorXd gradient = Eigen::VectorXd::Zero(x0.size());
  for (Eigen::Index k = 0; k < x0.size(); ++k) {
    const double step = 1e-3 * std::sqrt(cov(k, k));
    if (!(step > 0.0)) continue;
    Eigen::VectorXd up = x0, down = x0;
    up(k) += step;
    down(k) -= step;
    gradient(k) = (f(law_at(c, up)) - f(law_at(c, down))) / (2.0 * step);
  }
  return gradient.dot(cov * gradient);
}

Percentiles percentiles(std::vector<double> values) {
  if (values.empty()) throw InputError("percentiles of no values");
  std::sort(values.begin(), values.end());
  const auto at = [&](double q) {
    const double position = q * static_cast<double>(values.size() - 1);
    const auto below = static_cast<std::size_t>(std::floor(position));
    const std::size_t above = std::min(below + 1, values.size() - 1);
    const double fraction = position - static_cast<double>(below);
    return values[below] + fraction * (values[above] - values[below]);
  };
  return {at(0.158655), at(0.5), at(0.841345)};
}

}  // namespace craterkit::scaling
