#include "support/sedov.hpp"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace craterkit::test_support {
namespace {

// State y = (psi, phi, pi, J) as functions of s = ln xi; J(xi) = int_xi^1 (psi phi^2/2 + pi/(g-1)) x^2 dx.
int similarity_rhs(double s, const double y[], double dyds[], void* params) {
  const double g = *static_cast<const double*>(params);
  const double xi = std::exp(s);
  const double psi = y[0], phi = y[1], pi = y[2];
  const double w = phi - xi;
  const double dphi = (1.5 * phi * psi * w - 3.0 * pi + 2.0 * g * pi * phi / xi) / (psi * w * w - g * pi);
  const double divergence = 2.0 * phi / xi + dphi;  // (1/xi^2) d(xi^2 phi)/dxi
  const double dpsi = -psi * divergence / w;
  const double dpi = pi * (3.0 - g * divergence) / w;
  dyds[0] = xi * dpsi;
  dyds[1] = xi * dphi;
  dyds[2] = xi * dpi;
  dyds[3] = -xi * xi * xi * (0.5 * psi * phi * phi + pi / (g - 1.0));
  return GSL_SUCCESS;
}

}  // namespace

SedovSolution::SedovSolution(double gamma) : gamma_(gamma) {
  if (!(gamma > 1.0 && gamma <= 3.0)) {
    throw std::invalid_argument("SedovSolution: gamma must be in (1, 3], got " + std::to_string(gamma));
  }
  // Output grid (descending): uniform in xi down to 0.01 where the profiles vary most, then
  // logarithmic to xi_min. Inward integration towards the singular centre amplifies round-off as
  // xi^-2 (phi off by ~3e-15/xi^2), so it stops at xi_min = 1e-3 and the centre uses the asymptotic
  // forms (Sedov 1959) anchored there: phi ~ xi, pi constant, psi ~ xi^(3/(gamma-1)). The energy
  // inside xi_min, pi(0)/(gamma-1) xi_min^3/3 ~ 1e-10, is added to the integral.
  constexpr int uniform_points = 4000;
  constexpr int log_points = 200;
  constexpr double xi_split = 0.01;
  constexpr double xi_min = 1e-3;
  std::vector<double> grid;
  for (int k = 0; k < uniform_points; ++k) grid.push_back(1.0 - (1.0 - xi_split) * k / uniform_points);
  for (int k = 0; k <= log_points; ++k) {
    grid.push_back(xi_split * std::pow(xi_min / xi_split, static_cast<double>(k) / log_points));
  }

  double g = gamma;
  gsl_odeiv2_system system{&similarity_rhs, nullptr, 4, &g};
  gsl_odeiv2_driver* driver =
      gsl_odeiv2_driver_alloc_y_new(&system, gsl_odeiv2_step_rk8pd, -1e-6, 1e-13, 1e-13);
  std::array<double, 4> y{(g + 1.0) / (g - 1.0), 2.0 / (g + 1.0), 2.0 / (g + 1.0), 0.0};
  double s = 0.0;
  std::vector<double> xi, psi, phi, pi;
  for (const double target_xi : grid) {
    const double target = std::log(target_xi);
    if (target < s) {
      const int status = gsl_odeiv2_driver_apply(driver, &s, target, y.data());
      if (status != GSL_SUCCESS) {
        gsl_odeiv2_driver_free(driver);
        throw std::runtime_error("SedovSolution: similarity ODE integration failed at xi = " +
                                 std::to_string(target_xi));
      }
    }
    xi.push_back(target_xi);
    psi.push_back(y[0]);
    phi.push_back(y[1]);
    pi.push_back(y[2]);
  }
  gsl_odeiv2_driver_free(driver);
  // Energy integral; the core below xi_min adds pi(0)/(g-1) xi_min^3/3 (its kinetic part ~ xi_min^(5+4.5)).
  const double integral = y[3] + pi.back() / (g - 1.0) * xi_min * xi_min * xi_min / 3.0;
  xi0_ = std::pow(25.0 / (16.0 * std::numbers::pi * integral), 0.2);

  xi_.assign(xi.rbegin(), xi.rend());
  psi_.assign(psi.rbegin(), psi.rend());
  phi_.assign(phi.rbegin(), phi.rend());
  pi_.assign(pi.rbegin(), pi.rend());
}

// Piecewise power law (linear in ln value against ln xi): exact for the power-law centre, and on the
// fine uniform grid near the shock as accurate as linear interpolation. Below the first grid point the
// power law continues with the given exponent.
double SedovSolution::interpolate(const std::vector<double>& values, double xi,
                                  double centre_exponent) const {
  if (xi >= xi_.back()) return values.back();
  if (xi <= 0.0) return centre_exponent > 0.0 ? 0.0 : values.front();
  if (xi <= xi_.front()) return values.front() * std::pow(xi / xi_.front(), centre_exponent);
  const auto upper = std::upper_bound(xi_.begin(), xi_.end(), xi);
  const auto k = static_cast<std::size_t>(upper - xi_.begin());
  const double t = std::log(xi / xi_[k - 1]) / std::log(xi_[k] / xi_[k - 1]);
  return values[k - 1] * std::pow(values[k] / values[k - 1], t);
}

double SedovSolution::density_ratio(double xi) const {
  return interpolate(psi_, xi, 3.0 / (gamma_ - 1.0));
}
double SedovSolution::velocity_ratio(double xi) const {
  return interpolate(phi_, xi, 1.0);
}
double SedovSolution::pressure_ratio(double xi) const {
  return interpolate(pi_, xi, 0.0);
}

double SedovSolution::shock_radius(double energy, double ambient_density, double time) const {
  return xi0_ * std::pow(energy * time * time / ambient_density, 0.2);
}

SedovState SedovSolution::state(double radius, double energy, double ambient_density, double time) const {
  const double r_s = shock_radius(energy, ambient_density, time);
  const double xi = radius / r_s;
  if (xi > 1.0) return SedovState{ambient_density, 0.0, 0.0};
  const double shock_speed = 0.4 * r_s / time;
  return SedovState{ambient_density * density_ratio(xi), shock_speed * velocity_ratio(xi),
                    ambient_density * shock_speed * shock_speed * pressure_ratio(xi)};
}

}  // namespace craterkit::test_support
