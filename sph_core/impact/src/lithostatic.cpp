#include "craterkit/impact/lithostatic.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include "craterkit/common/input_error.hpp"
#include "craterkit/sph/physics/eos.hpp"
#include "craterkit/sph/physics/p_alpha.hpp"

namespace craterkit::impact {

using namespace sph;

namespace {

// Root of P_m(rho_m, 0) = target (>= 0) for rho_m >= rho0: the cold compression curve rises
// monotonically from P_m(rho0, 0) = 0 (Tillotson: A chi + B chi^2; linear law: A chi).
double cold_matrix_density(const Material& material, double target) {
  const auto reference = solid_reference(material.eos);
  if (!reference) {
    throw InputError("material \"" + material.name +
                     "\": a lithostatic target needs a solid equation of state (an ideal gas has no cold "
                     "pressure)");
  }
  const double rho0 = reference->density;
  if (target <= 0.0) return rho0;
  const auto excess = [&](double rho_m) { return evaluate(material.eos, rho_m, 0.0).pressure - target; };
  double lo = rho0;
  double f_lo = excess(lo);
  double hi = rho0 * (1.0 + std::max(2.0 * target / reference->bulk_modulus, 1e-14));
  double f_hi = excess(hi);
  for (int expand = 0; f_hi <= 0.0; ++expand) {
    if (expand > 200) {
      throw InputError("material \"" + material.name + "\": no density reaches the lithostatic pressure " +
                       std::to_string(target) + " Pa");
    }
    lo = hi;
    f_lo = f_hi;
    hi = rho0 + 2.0 * (hi - rho0);
    f_hi = excess(hi);
  }
  // Brent's method (GSL) on the bracket [lo, hi] with f(lo) <= 0 < f(hi).
  if (f_lo == 0.0) return lo;
  gsl_function function{
      [](double rho_m, void* params) { return (*static_cast<decltype(excess)*>(params))(rho_m); },
      const_cast<void*>(static_cast<const void*>(&excess))};
  gsl_root_fsolver* solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  gsl_root_fsolver_set(solver, &function, lo, hi);
  double root = 0.5 * (lo + hi);
  for (int iteration = 0; iteration < 300; ++iteration) {
    gsl_root_fsolver_iterate(solver);
    root = gsl_root_fsolver_root(solver);
    if (gsl_root_test_interval(gsl_root_fsolver_x_lower(solver), gsl_root_fsolver_x_upper(solver), 0.0,
                               1e-15) == GSL_SUCCESS) {
      break;
    }
  }
  gsl_root_fsolver_free(solver);
  return root;
}

}  // namespace

LithostaticState lithostatic_state(const Material& material, double pressure) {
  if (!material.porosity) return {cold_matrix_density(material, pressure), 1.0};
  const double alpha = crush_curve_distention(material.porosity->crush_curve, pressure);
  return {cold_matrix_density(material, alpha * pressure) / alpha, alpha};
}

double lithostatic_pressure_after(const Material& material, double p_top, double thickness, double g,
                                  int substeps) {
  if (!(thickness > 0.0) || !(g > 0.0)) return p_top;
  const auto rate = [&](double p) { return g * lithostatic_state(material, p).density; };
  const auto rk4 = [&](double p, double step) {
    const double k1 = rate(p);
    const double k2 = rate(p + 0.5 * step * k1);
    const double k3 = rate(p + 0.5 * step * k2);
    const double k4 = rate(p + step * k3);
    return p + step * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
  };
  // rho(P) has kinks where the crush curve changes branch (P_e, P_t, P_s): a step across one is split
  // where P reaches it (linear estimate, P(depth) being nearly linear), so RK4 keeps its order.
  double kinks[3] = {0.0, 0.0, 0.0};
  int n_kinks = 0;
  if (material.porosity) {
    const PAlphaParameters& c = material.porosity->crush_curve;
    kinks[0] = c.elastic_pressure;
    kinks[1] = c.transition_pressure;
    kinks[2] = c.solid_pressure;
    n_kinks = 3;
  }
  const double step = thickness / substeps;
  double p = p_top;
  for (int s = 0; s < substeps; ++s) {
    double next = rk4(p, step);
    for (int k = 0; k < n_kinks; ++k) {
      if (p < kinks[k] && next > kinks[k]) {
        const double part = step * (kinks[k] - p) / (next - p);
        next = rk4(rk4(p, part), step - part);
        break;
      }
    }
    p = next;
  }
  return p;
}

namespace {

double adaptive_step(const Material& material, double p_top, double thickness, double g, double tolerance,
                     int depth) {
  const double one = lithostatic_pressure_after(material, p_top, thickness, g, 1);
  const double two = lithostatic_pressure_after(material, p_top, thickness, g, 2);
  if (depth >= 30 || std::abs(two - one) <= tolerance * std::abs(two)) return two;
  const double half = 0.5 * thickness;
  const double middle = adaptive_step(material, p_top, half, g, tolerance, depth + 1);
  return adaptive_step(material, middle, half, g, tolerance, depth + 1);
}

}  // namespace

double lithostatic_pressure_adaptive(const Material& material, double p_top, double thickness, double g,
                                     double relative_tolerance) {
  if (!(thickness > 0.0) || !(g > 0.0)) return p_top;
  return adaptive_step(material, p_top, thickness, g, relative_tolerance, 0);
}

}  // namespace craterkit::impact
