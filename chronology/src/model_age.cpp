#include "craterkit/chronology/model_age.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"

namespace craterkit::chronology {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Production quantities at one diameter: r(D) and, for the cap, -dr/dD.
struct ProductionPoint {
  double diameter = kInf;
  double rate = 0.0;        // r(D)
  double rate_slope = 0.0;  // -dr/dD
};

ProductionPoint evaluate(const ProductionFunction& production, double d, bool need_slope) {
  ProductionPoint p;
  p.diameter = d;
  if (std::isinf(d)) return p;
  p.rate = production(d);
  if (!(p.rate >= 0.0) || !std::isfinite(p.rate)) {
    throw InputError("production rate at D = " + format_number(d) + " m is " + format_number(p.rate) +
                     "; expected a finite value >= 0");
  }
  if (need_slope) {
    constexpr double h = 1e-4;
    p.rate_slope = (production(d * (1.0 - h)) - production(d * (1.0 + h))) / (2.0 * h * d);
  }
  return p;
}

double cumulative(const EquilibriumCap& cap, const ProductionPoint& p, double t) {
  if (std::isinf(p.diameter)) return 0.0;
  return expected_cumulative_density(cap, p.diameter, t, p.rate);
}

// -dN/dD at (D, t); without the cap t (-dr/dD). With the cap (N_eq = c D^-2, x = t r / N_eq):
//   -dN/dD = (2 N_eq / D)(1 - e^-x) + e^-x t (-dr/dD - 2 r / D).
double differential(const EquilibriumCap& cap, const ProductionPoint& p, double t) {
  if (!cap.enabled) return t * p.rate_slope;
  const double n_eq = equilibrium_density(cap, p.diameter);
  const double x = t * p.rate / n_eq;
  const double e = std::exp(-x);
  return (2.0 * n_eq / p.diameter) * (-std::expm1(-x)) + e * t * (p.rate_slope - 2.0 * p.rate / p.diameter);
}

struct Likelihood {
  EquilibriumCap cap;
  std::function<double(double)> clock;  // empty: identity
  double area = 0.0;
  // Unbinned.
  ProductionPoint lower, upper;
  std::vector<ProductionPoint> craters;
  std::vector<double> weights;
  double weight_sum = 0.0;
  // Binned: edges (bins.size() + 1, last may be infinite) and counts.
  std::vector<ProductionPoint> edges;
  std::vector<double> bin_counts;

  double operator()(double age) const {
    if (!(age > 0.0)) return weight_sum > 0.0 ? -kInf : 0.0;
    const double t = clock ? clock(age) : age;  // years of present-day flux
    if (!edges.empty()) {
      double sum = 0.0;
      for (std::size_t j = 0; j < bin_counts.size(); ++j) {
        const double lambda = area * (cumulative(cap, edges[j], t) - cumulative(cap, edges[j + 1], t));
        if (lambda <= 0.0) {
          if (bin_counts[j] > 0.0) return -kInf;
          continue;
        }
        sum += bin_counts[j] * std::log(lambda) - lambda;
      }
      return sum;
    }
    double sum = -area * (cumulative(cap, lower, t) - cumulative(cap, upper, t));
    if (!cap.enabled) return sum + weight_sum * std::log(t);  // the t-independent sum of ln(-A dr/dD) dropped
    for (std::size_t i = 0; i < craters.size(); ++i) {
      const double n = differential(cap, craters[i], t);
      if (!(n > 0.0)) return -kInf;
      sum += weights[i] * std::log(area * n);
    }
    return sum;
  }
};

}  // namespace

double density_quantile(const std::vector<double>& grid, const std::vector<double>& density, double q) {
  std::vector<double> cdf(grid.size(), 0.0);
  for (std::size_t i = 1; i < grid.size(); ++i) {
    cdf[i] = cdf[i - 1] + 0.5 * (density[i] + density[i - 1]) * (grid[i] - grid[i - 1]);
  }
  const double total = cdf.back();
  const double target = q * total;
  auto it = std::lower_bound(cdf.begin(), cdf.end(), target);
  if (it == cdf.begin()) return grid.front();
  if (it == cdf.end()) return grid.back();
  const std::size_t k = static_cast<std::size_t>(it - cdf.begin());
  const double f = (target - cdf[k - 1]) / (cdf[k] - cdf[k - 1]);
  return grid[k - 1] + f * (grid[k] - grid[k - 1]);
}

AgeEstimate fit_model_age(const CraterCounts& counts, const ProductionFunction& production,
                          const AgeFitOptions& options) {
  if (counts.buffered && !options.weight_by_fraction) {
    throw InputError(counts.source +
                     ": buffered counts (reference areas) need their weights: counting each crater whole is "
                     "not allowed for them");
  }
  validate(counts);
  validate(options.cap);
  if (!(options.max_age > 0.0))
    throw InputError("maximum age " + format_number(options.max_age) + " yr must be > 0");
  if (options.grid_points < 101) throw InputError("age grid needs at least 101 points");
  AgeEstimate out;
  Likelihood like;
  like.cap = options.cap;
  like.clock = options.clock;
  // Age in years from years of present-day flux (the inverse of the clock, by bisection).
  const auto age_of = [&](double tau) {
    if (!options.clock) return tau;
    double lo = 0.0, hi = options.max_age;
    while (options.clock(hi) < tau && hi < 1e3 * options.max_age) hi *= 2.0;
    for (int it = 0; it < 200 && hi - lo > 1e-13 * hi; ++it) {
      const double mid = 0.5 * (lo + hi);
      (options.clock(mid) < tau ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  };
  like.area = counts.area;

  // Cumulative points for the classical fit: (D, N(>=D) per m^2).
  std::vector<std::pair<double, double>> cumulative_points;

  if (counts.binned()) {
    const auto& bins = counts.bins;
    const double dmin = options.min_diameter > 0.0 ? options.min_diameter : bins.front().diameter;
    std::vector<std::size_t> used;
    for (std::size_t j = 0; j < bins.size(); ++j) {
      if (bins[j].diameter >= dmin && bins[j].diameter <= options.max_diameter) used.push_back(j);
    }
    if (used.empty()) {
      throw InputError(counts.source + ": no bins with diameters in the fit range [" + format_number(dmin) +
                       ", " + format_number(options.max_diameter) + "] m");
    }
    for (std::size_t j : used) {
      like.edges.push_back(evaluate(production, bins[j].diameter, false));
      const double next = j + 1 < bins.size() ? bins[j + 1].cumulative_count : 0.0;
      like.bin_counts.push_back(bins[j].cumulative_count - next);
      cumulative_points.emplace_back(bins[j].diameter, bins[j].cumulative_count / counts.area);
    }
    const std::size_t last = used.back();
    like.edges.push_back(
        evaluate(production, last + 1 < bins.size() ? bins[last + 1].diameter : kInf, false));
    out.min_diameter = like.edges.front().diameter;
    out.max_diameter = like.edges.back().diameter;
    out.craters_in_range = std::accumulate(like.bin_counts.begin(), like.bin_counts.end(), 0.0);
    like.weight_sum = out.craters_in_range;
    out.production_in_range = like.edges.front().rate - like.edges.back().rate;
  } else {
    if (counts.diameters.empty()) throw InputError(counts.source + ": no craters in the count");
    const double dmin = options.min_diameter > 0.0
                            ? options.min_diameter
                            : *std::min_element(counts.diameters.begin(), counts.diameters.end());
    if (!(options.max_diameter > dmin)) {
      throw InputError("fit range: maximum diameter " + format_number(options.max_diameter) +
                       " m must exceed minimum " + format_number(dmin) + " m");
    }
    out.min_diameter = dmin;
    out.max_diameter = options.max_diameter;
    like.lower = evaluate(production, dmin, false);
    like.upper = evaluate(production, options.max_diameter, false);
    // Sort by decreasing diameter for the cumulative counts.
    std::vector<std::size_t> order(counts.diameters.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](auto a, auto b) { return counts.diameters[a] > counts.diameters[b]; });
    double running = 0.0;
    for (std::size_t idx : order) {
      const double d = counts.diameters[idx];
      running += counts.fractions[idx];
      if (d < dmin || d >= options.max_diameter) continue;
      like.craters.push_back(options.cap.enabled ? evaluate(production, d, true)
                                                 : ProductionPoint{d, 0.0, 0.0});
      const double weight = options.weight_by_fraction ? counts.fractions[idx] : 1.0;
      like.weights.push_back(weight);
      like.weight_sum += weight;
      cumulative_points.emplace_back(d, running / counts.area);
    }
    out.craters_in_range = like.weight_sum;
    out.production_in_range = like.lower.rate - like.upper.rate;
  }
  if (!(out.production_in_range > 0.0)) {
    throw InputError("the production function makes no craters in the fit range [" +
                     format_number(out.min_diameter) + ", " + format_number(out.max_diameter) +
                     "] m; widen the range");
  }

  // Coarse logarithmic scan around the uncapped estimate, then a fine grid where the likelihood is
  // within e^-40 of its maximum.
  const double t_guess =
      age_of(std::max(out.craters_in_range, 1.0) / (counts.area * out.production_in_range));
  const double t_lo = std::min(t_guess * 1e-6, options.max_age * 1e-9);
  const double t_hi = options.max_age;
  const std::size_t n_coarse = 800;
  std::vector<double> coarse(n_coarse), coarse_ll(n_coarse);
  double best = -kInf;
  // The log-posterior up to a constant: the likelihood, plus ln(d clock/dt) for a prior uniform in density.
  const auto log_posterior = [&](double t) {
    double value = like(t);
    if (options.prior_uniform_in_density && options.clock && std::isfinite(value)) {
      const double h = 1e-6 * t;
      value += std::log((options.clock(t + h) - options.clock(t - h)) / (2.0 * h));
    }
    return value;
  };
  for (std::size_t i = 0; i < n_coarse; ++i) {
    coarse[i] = t_lo * std::pow(t_hi / t_lo, static_cast<double>(i) / (n_coarse - 1));
    coarse_ll[i] = log_posterior(coarse[i]);
    best = std::max(best, coarse_ll[i]);
  }
  if (!std::isfinite(best))
    throw InputError("the crater count has zero likelihood for every age up to the maximum age");
  std::size_t first = n_coarse, last = 0;
  for (std::size_t i = 0; i < n_coarse; ++i) {
    if (coarse_ll[i] > best - 40.0) {
      first = std::min(first, i);
      last = i;
    }
  }
  // The fine grid is logarithmic: it resolves a narrow peak as well as a density spread over decades
  // (saturated counts); the mass below t_lo (a millionth of the uncapped estimate) is negligible.
  const double grid_lo = first == 0 ? coarse.front() : coarse[first - 1];
  const double grid_hi = last + 1 < n_coarse ? coarse[last + 1] : t_hi;
  out.reaches_max_age = last + 1 >= n_coarse;
  const std::size_t n = options.grid_points;
  out.age_grid.resize(n);
  out.density.resize(n);
  std::vector<double> ll(n);
  double fine_best = -kInf;
  for (std::size_t i = 0; i < n; ++i) {
    out.age_grid[i] =
        grid_lo * std::pow(grid_hi / grid_lo, static_cast<double>(i) / static_cast<double>(n - 1));
    ll[i] = log_posterior(out.age_grid[i]);
    fine_best = std::max(fine_best, ll[i]);
  }
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    out.density[i] = std::isfinite(ll[i]) ? std::exp(ll[i] - fine_best) : 0.0;
  for (std::size_t i = 1; i < n; ++i) {
    total += 0.5 * (out.density[i] + out.density[i - 1]) * (out.age_grid[i] - out.age_grid[i - 1]);
  }
  for (auto& d : out.density) d /= total;
  out.mode = out.age_grid[static_cast<std::size_t>(std::max_element(out.density.begin(), out.density.end()) -
                                                   out.density.begin())];
  out.median = density_quantile(out.age_grid, out.density, 0.5);
  out.sigma1_low = density_quantile(out.age_grid, out.density, 0.158655);
  out.sigma1_high = density_quantile(out.age_grid, out.density, 0.841345);
  out.sigma2_low = density_quantile(out.age_grid, out.density, 0.0227501);
  out.sigma2_high = density_quantile(out.age_grid, out.density, 0.9772499);

  // Classical cumulative fit: least squares of ln N(>=D) over the points in range.
  if (options.cumulative_fit && !cumulative_points.empty()) {
    std::vector<ProductionPoint> pts;
    for (const auto& [d, nobs] : cumulative_points) {
      (void)nobs;
      pts.push_back(counts.binned() ? ProductionPoint{d, production(d), 0.0}
                                    : evaluate(production, d, false));
    }
    auto misfit = [&](double log_t) {
      double s = 0.0;
      for (std::size_t i = 0; i < pts.size(); ++i) {
        const double age = std::exp(log_t);
        const double model = cumulative(options.cap, pts[i], options.clock ? options.clock(age) : age);
        const double r = std::log(cumulative_points[i].second) - std::log(model);
        s += r * r;
      }
      return s;
    };
    double log_t = 0.0;
    if (!options.cap.enabled) {
      for (std::size_t i = 0; i < pts.size(); ++i)
        log_t += std::log(cumulative_points[i].second / pts[i].rate);
      log_t /= static_cast<double>(pts.size());
      log_t = std::log(age_of(std::exp(log_t)));
    } else {
      // Golden-section search on ln t (the misfit is unimodal in t for a monotone cap).
      double a = std::log(t_lo), b = std::log(t_hi);
      const double g = 0.5 * (std::sqrt(5.0) - 1.0);
      double c = b - g * (b - a), d = a + g * (b - a);
      for (int it = 0; it < 200; ++it) {
        if (misfit(c) < misfit(d))
          b = d;
        else
          a = c;
        c = b - g * (b - a);
        d = a + g * (b - a);
      }
      log_t = 0.5 * (a + b);
    }
    out.cumulative_fit_age = std::exp(log_t);
    double n_total = 0.0;  // N(>= D_min of the range)
    for (const auto& point : cumulative_points) n_total = std::max(n_total, point.second * counts.area);
    // sigma of N / sqrt(N) relative, carried through the clock: sigma_t = (tau / sqrt(N)) / (d tau / d t).
    double rate = 1.0;
    if (options.clock) {
      const double t = out.cumulative_fit_age, h = 1e-6 * t;
      rate = (options.clock(t + h) - options.clock(t - h)) / (2.0 * h) * t / options.clock(t);
    }
    out.cumulative_fit_sigma = n_total > 0.0 ? out.cumulative_fit_age / std::sqrt(n_total) / rate : kInf;
  }
  return out;
}

}  // namespace craterkit::chronology
