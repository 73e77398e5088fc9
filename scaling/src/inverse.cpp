// Inverse problems of the point-source law: the impactor radius, the impact speed or the target strength that
// makes a given crater radius. Each is a one-dimensional root of a strictly monotonic function of the log of
// the unknown (d ln R / d ln a = 1 - mu/(2+mu) * gravity share > 0; R grows with U because both pi2 and pi3
// fall with U; R falls with Y because pi3 grows with it), so a root exists for every R > 0 whenever gravity
// or strength is > 0; for the strength, only for R below the gravity-regime radius (Y = 0). It is bracketed
// by stepping outwards in ln(unknown) with doubling steps and then polished by GSL's Brent solver.
#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <string>

#include <gsl/gsl_errno.h>
#include <gsl/gsl_roots.h>

#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/point_source.hpp"

namespace craterkit::scaling {
namespace {

// The range searched for the unknown, as ln(value / unit): 1e-30 .. 1e30 in SI units.
constexpr double kLnMin = -69.0;
constexpr double kLnMax = 69.0;

double call(double x, void* params) {
  return (*static_cast<std::function<double(double)>*>(params))(x);
}

// Root of the increasing function f on [kLnMin, kLnMax], starting the bracket search at x0.
// `what` names the unknown for the error message.
double solve_increasing(const std::function<double(double)>& f, double x0, const std::string& what) {
  // GSL's default handler aborts the program; errors are reported through return codes instead.
  static const bool handler_off = (gsl_set_error_handler_off(), true);
  (void)handler_off;

  x0 = std::clamp(x0, kLnMin, kLnMax);
  double lo = x0;
  double hi = x0;
  double f_lo = f(lo);
  double f_hi = f_lo;
  double step = 0.5;
  while (f_lo > 0.0 && lo > kLnMin) {  // root is below: walk down
    hi = lo;
    f_hi = f_lo;
    lo = std::max(lo - step, kLnMin);
    f_lo = f(lo);
    step *= 2.0;
  }
  while (f_hi < 0.0 && hi < kLnMax) {  // root is above: walk up
    lo = hi;
    f_lo = f_hi;
    hi = std::min(hi + step, kLnMax);
    f_hi = f(hi);
    step *= 2.0;
  }
  if (!std::isfinite(f_lo) || !std::isfinite(f_hi)) {
    throw InputError("no " + what + " found: the scaling law is not finite in the searched range");
  }
  if (f_lo == 0.0) return lo;
  if (f_hi == 0.0) return hi;
  if (f_lo > 0.0 || f_hi < 0.0) {
    throw InputError("no " + what + " between 1e-30 and 1e30 (SI) produces this crater radius");
  }

  std::function<double(double)> func = f;
  gsl_function gf{&call, &func};
  gsl_root_fsolver* solver = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (solver == nullptr) throw std::runtime_error("GSL could not allocate a root solver");
  gsl_root_fsolver_set(solver, &gf, lo, hi);
  int status = GSL_CONTINUE;
  double root = 0.5 * (lo + hi);
  for (int iteration = 0; iteration < 200 && status == GSL_CONTINUE; ++iteration) {
    if (gsl_root_fsolver_iterate(solver) != GSL_SUCCESS) break;
    root = gsl_root_fsolver_root(solver);
    status = gsl_root_test_interval(gsl_root_fsolver_x_lower(solver), gsl_root_fsolver_x_upper(solver), 1e-13,
                                    1e-14);
  }
  gsl_root_fsolver_free(solver);
  if (status != GSL_SUCCESS) {
    throw std::runtime_error("GSL Brent solver did not converge for the " + what);
  }
  return root;
}

void check_crater_radius(double crater_radius) {
  if (!(crater_radius > 0.0) || !std::isfinite(crater_radius)) {
    throw InputError("crater radius = " + format_number(crater_radius) +
                     " is not allowed: must be a finite number > 0");
  }
}

}  // namespace

double solve_impactor_radius(const ScalingLaw& law, double crater_radius_target, const Impactor& impactor,
                             const Target& target) {
  check_crater_radius(crater_radius_target);
  Impactor trial = impactor;
  trial.radius = crater_radius_target;
  (void)scaling::crater_radius(law, trial, target);  // validates the other inputs with clear messages
  const double ln_target = std::log(crater_radius_target);
  const auto f = [&](double ln_a) {
    Impactor probe = impactor;
    probe.radius = std::exp(ln_a);
    return std::log(scaling::crater_radius(law, probe, target)) - ln_target;
  };
  // Craters are typically 1-100 impactor radii: start a tenth of the crater radius.
  return std::exp(solve_increasing(f, ln_target - std::log(10.0), "impactor radius"));
}

double solve_velocity(const ScalingLaw& law, double crater_radius_target, const Impactor& impactor,
                      const Target& target) {
  check_crater_radius(crater_radius_target);
  Impactor trial = impactor;
  trial.velocity = 1000.0;
  (void)scaling::crater_radius(law, trial, target);
  const double ln_target = std::log(crater_radius_target);
  const auto f = [&](double ln_u) {
    Impactor probe = impactor;
    probe.velocity = std::exp(ln_u);
    return std::log(scaling::crater_radius(law, probe, target)) - ln_target;
  };
  return std::exp(solve_increasing(f, std::log(1000.0), "impact velocity"));
}

double solve_strength(const ScalingLaw& law, double crater_radius_target, const Impactor& impactor,
                      const Target& target) {
  check_crater_radius(crater_radius_target);
  Target gravity_only = target;
  gravity_only.strength = 0.0;
  const double gravity_radius = scaling::crater_radius(law, impactor, gravity_only);  // validates the inputs
  if (!(crater_radius_target < gravity_radius)) {
    throw InputError("crater radius = " + format_number(crater_radius_target) +
                     " m is not reached by any strength: it must be below the cohesionless (gravity-regime) "
                     "radius " +
                     format_number(gravity_radius) + " m of this impact");
  }
  const double ln_target = std::log(crater_radius_target);
  const auto f = [&](double ln_y) {  // increasing in ln Y: R falls as Y grows
    Target probe = target;
    probe.strength = std::exp(ln_y);
    return ln_target - std::log(scaling::crater_radius(law, impactor, probe));
  };
  // Start at the strength of the target's pi3 = 1e-4 (a typical boundary of the two regimes).
  const double start = std::log(1e-4 * target.density * impactor.velocity * impactor.velocity);
  return std::exp(solve_increasing(f, start, "target strength"));
}

}  // namespace craterkit::scaling
