#include "support/exact_riemann.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace craterkit::test_support {
namespace {

struct Side {
  double gamma, density, pressure, sound;
};

// Toro eqs. 4.6 (left) / 4.7 (right): shock branch for p > p_K, rarefaction branch otherwise.
double pressure_function(const Side& k, double p) {
  const double g = k.gamma;
  if (p > k.pressure) {
    const double a_k = 2.0 / ((g + 1.0) * k.density);
    const double b_k = (g - 1.0) / (g + 1.0) * k.pressure;
    return (p - k.pressure) * std::sqrt(a_k / (p + b_k));
  }
  return 2.0 * k.sound / (g - 1.0) * (std::pow(p / k.pressure, (g - 1.0) / (2.0 * g)) - 1.0);
}

// Density behind the wave facing side k (Toro 4.19/4.32 shock, 4.23/4.34 rarefaction).
double star_density(const Side& k, double p_star) {
  const double g = k.gamma;
  const double ratio = p_star / k.pressure;
  if (p_star > k.pressure) {
    const double gr = (g - 1.0) / (g + 1.0);
    return k.density * (ratio + gr) / (gr * ratio + 1.0);
  }
  return k.density * std::pow(ratio, 1.0 / g);
}

struct PressureEquation {
  Side left, right;
  double du;
  double operator()(double p) const { return pressure_function(left, p) + pressure_function(right, p) + du; }
};

double call_equation(double p, void* params) {
  return (*static_cast<PressureEquation*>(params))(p);
}

}  // namespace

ExactRiemannSolver::ExactRiemannSolver(double gamma, const GasState& left, const GasState& right)
    : gamma_(gamma), left_(left), right_(right) {
  if (!(gamma > 1.0)) throw std::invalid_argument("ExactRiemannSolver: gamma must be > 1");
  if (!(left.density > 0 && right.density > 0 && left.pressure > 0 && right.pressure > 0)) {
    throw std::invalid_argument("ExactRiemannSolver: densities and pressures must be > 0");
  }
  sound_left_ = std::sqrt(gamma * left.pressure / left.density);
  sound_right_ = std::sqrt(gamma * right.pressure / right.density);
  const double du = right.velocity - left.velocity;
  if (du >= 2.0 * (sound_left_ + sound_right_) / (gamma - 1.0)) {
    throw std::domain_error("ExactRiemannSolver: the initial data generate a vacuum");
  }
  PressureEquation equation{{gamma, left.density, left.pressure, sound_left_},
                            {gamma, right.density, right.pressure, sound_right_},
                            du};
  // f is monotonically increasing in p (Toro section 4.3.1) and f(0) < 0 without vacuum: bracket
  // [0, p_hi] with p_hi doubled from max(p_L, p_R) until f(p_hi) > 0.
  double lower = 0.0;
  double upper = std::max(left.pressure, right.pressure);
  while (equation(upper) <= 0.0) {
    lower = upper;
    upper *= 2.0;
  }
  gsl_function function{&call_equation, &equation};
  std::unique_ptr<gsl_root_fsolver, decltype(&gsl_root_fsolver_free)> solver(
      gsl_root_fsolver_alloc(gsl_root_fsolver_brent), &gsl_root_fsolver_free);
  gsl_root_fsolver_set(solver.get(), &function, lower, upper);
  int status = GSL_CONTINUE;
  for (int iteration = 0; iteration < 200 && status == GSL_CONTINUE; ++iteration) {
    gsl_root_fsolver_iterate(solver.get());
    status = gsl_root_test_interval(gsl_root_fsolver_x_lower(solver.get()),
                                    gsl_root_fsolver_x_upper(solver.get()), 0.0, 1e-15);
  }
  if (status != GSL_SUCCESS) throw std::runtime_error("ExactRiemannSolver: p* did not converge");
  const double p = gsl_root_fsolver_root(solver.get());
  star_.pressure = p;
  // Toro eq. 4.9.
  star_.velocity = 0.5 * (left.velocity + right.velocity) +
                   0.5 * (pressure_function(equation.right, p) - pressure_function(equation.left, p));
  star_.density_left = star_density(equation.left, p);
  star_.density_right = star_density(equation.right, p);
}

GasState ExactRiemannSolver::sample(double s) const {
  const double g = gamma_;
  const double p_star = star_.pressure;
  const double u_star = star_.velocity;
  if (s <= u_star) {  // left of the contact
    const GasState& l = left_;
    const double c = sound_left_;
    if (p_star > l.pressure) {  // left shock, speed Toro eq. 4.52
      const double shock =
          l.velocity - c * std::sqrt((g + 1.0) / (2.0 * g) * p_star / l.pressure + (g - 1.0) / (2.0 * g));
      return s <= shock ? l : GasState{star_.density_left, u_star, p_star};
    }
    const double head = l.velocity - c;  // left rarefaction, Toro eqs. 4.54-4.56
    const double c_star = c * std::pow(p_star / l.pressure, (g - 1.0) / (2.0 * g));
    const double tail = u_star - c_star;
    if (s <= head) return l;
    if (s >= tail) return GasState{star_.density_left, u_star, p_star};
    const double bracket = 2.0 / (g + 1.0) + (g - 1.0) / ((g + 1.0) * c) * (l.velocity - s);
    return GasState{l.density * std::pow(bracket, 2.0 / (g - 1.0)),
                    2.0 / (g + 1.0) * (c + 0.5 * (g - 1.0) * l.velocity + s),
                    l.pressure * std::pow(bracket, 2.0 * g / (g - 1.0))};
  }
  const GasState& r = right_;  // right of the contact
  const double c = sound_right_;
  if (p_star > r.pressure) {  // right shock, Toro eq. 4.59
    const double shock =
        r.velocity + c * std::sqrt((g + 1.0) / (2.0 * g) * p_star / r.pressure + (g - 1.0) / (2.0 * g));
    return s >= shock ? r : GasState{star_.density_right, u_star, p_star};
  }
  const double head = r.velocity + c;  // right rarefaction, Toro eqs. 4.61-4.63
  const double c_star = c * std::pow(p_star / r.pressure, (g - 1.0) / (2.0 * g));
  const double tail = u_star + c_star;
  if (s >= head) return r;
  if (s <= tail) return GasState{star_.density_right, u_star, p_star};
  const double bracket = 2.0 / (g + 1.0) - (g - 1.0) / ((g + 1.0) * c) * (r.velocity - s);
  return GasState{r.density * std::pow(bracket, 2.0 / (g - 1.0)),
                  2.0 / (g + 1.0) * (-c + 0.5 * (g - 1.0) * r.velocity + s),
                  r.pressure * std::pow(bracket, 2.0 * g / (g - 1.0))};
}

}  // namespace craterkit::test_support
