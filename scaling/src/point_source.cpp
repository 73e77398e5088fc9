// Forward point-source law, pi groups, regimes and limits (docs/physics.md section 6).
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "craterkit/common/checks.hpp"
#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/point_source.hpp"
#include "point_source_formula.hpp"

namespace craterkit::scaling {
namespace {

void check_inputs(const Impactor& impactor, const Target& target) {
  require_positive(impactor.radius, "impactor radius");
  require_positive(impactor.density, "impactor density");
  require_positive(impactor.velocity, "impact velocity");
  require_positive(target.density, "target density");
  require_non_negative(target.gravity, "gravity");
  require_non_negative(target.strength, "strength");
  if (target.gravity == 0.0 && target.strength == 0.0) {
    throw InputError(
        "gravity and strength are both 0: the point-source law then has no finite crater (at least one must "
        "be > 0)");
  }
}

// The constants a given impact actually uses must be given (a set may leave one out, as NaN).
void check_needed_constants(const ScalingLaw& law, const PiGroups& pi) {
  const bool needs_c1 = law.form == Form::holsapple || pi.pi2 > 0.0;
  const bool needs_c2 = pi.pi3 > 0.0;
  if (needs_c1 && std::isnan(law.coefficient_1)) {
    throw InputError(
        coefficient_name(law.form, 1) +
        " is not given by this constant set but this impact needs it (gravity > 0): supply it (--" +
        coefficient_name(law.form, 1) + ")");
  }
  if (needs_c2 && std::isnan(law.coefficient_2)) {
    throw InputError(
        coefficient_name(law.form, 2) +
        " is not given by this constant set but this impact needs it (strength > 0): supply it (--" +
        coefficient_name(law.form, 2) + ")");
  }
}

detail::LogPiGroups<double> log_pi_groups(const PiGroups& pi) {
  detail::LogPiGroups<double> out;
  out.has_gravity = pi.pi2 > 0.0;
  out.has_strength = pi.pi3 > 0.0;
  out.ln_pi2 = out.has_gravity ? std::log(pi.pi2) : 0.0;
  out.ln_pi3 = out.has_strength ? std::log(pi.pi3) : 0.0;
  out.ln_pi4 = std::log(pi.pi4);
  return out;
}

// (m/rho)^(1/3): converts pi_R to R.
double length_scale(const Impactor& impactor, const Target& target) {
  return std::cbrt(impactor_mass(impactor) / target.density);
}

}  // namespace

ScalingLaw convert(const ScalingLaw& law, Form to) {
  if (law.form == to) return law;
  ScalingLaw out = law;
  out.form = to;
  out.coefficient_1 = law.coefficient_1;  // K1 = H1
  if (to == Form::holsapple) {
    out.coefficient_2 = std::pow(law.coefficient_1 / law.coefficient_2, 2.0 / law.mu);  // K2 = (H1/H2)^(2/mu)
  } else {
    out.coefficient_2 = law.coefficient_1 * std::pow(law.coefficient_2, -law.mu / 2.0);  // H2 = K1 K2^(-mu/2)
  }
  return out;
}

void validate(const ScalingLaw& law) {
  require_positive(law.coefficient_1, "scaling constant " + coefficient_name(law.form, 1));
  require_positive(law.coefficient_2, "scaling constant " + coefficient_name(law.form, 2));
  require_positive(law.mu, "scaling constant mu (1/3 momentum .. 2/3 energy scaling)");
  require_non_negative(law.nu, "scaling constant nu (about 0.4)");
}

PiGroups pi_groups(const Impactor& impactor, const Target& target) {
  const double u2 = impactor.velocity * impactor.velocity;
  return PiGroups{target.gravity * impactor.radius / u2, target.strength / (target.density * u2),
                  target.density / impactor.density};
}

double impactor_mass(const Impactor& impactor) {
  return 4.0 / 3.0 * std::numbers::pi * impactor.radius * impactor.radius * impactor.radius *
         impactor.density;
}

double pi_R(const ScalingLaw& law, const PiGroups& pi) {
  if (!(pi.pi2 >= 0.0) || !(pi.pi3 >= 0.0) || !(pi.pi2 > 0.0 || pi.pi3 > 0.0) || !(pi.pi4 > 0.0)) {
    throw InputError("pi groups (pi2 = " + format_number(pi.pi2) + ", pi3 = " + format_number(pi.pi3) +
                     ", pi4 = " + format_number(pi.pi4) +
                     ") are not allowed: need pi2 >= 0, pi3 >= 0, not both 0, pi4 > 0");
  }
  check_needed_constants(law, pi);
  const auto log_pi = log_pi_groups(pi);
  // A constant that the impact does not use may be NaN (left out by its set); feed a harmless value.
  const double ln_c1 = std::isnan(law.coefficient_1) ? 0.0 : std::log(law.coefficient_1);
  const double ln_c2 = std::isnan(law.coefficient_2) ? 0.0 : std::log(law.coefficient_2);
  return std::exp(detail::log_pi_R(law.form, ln_c1, ln_c2, law.mu, law.nu, log_pi));
}

double crater_radius(const ScalingLaw& law, const Impactor& impactor, const Target& target) {
  check_inputs(impactor, target);
  return pi_R(law, pi_groups(impactor, target)) * length_scale(impactor, target);
}

double radius_ratio(const ScalingLaw& law, const Impactor& impactor, const Target& target) {
  return crater_radius(law, impactor, target) / impactor.radius;
}

double gravity_limit_radius(const ScalingLaw& law, const Impactor& impactor, const Target& target) {
  Target gravity_only = target;
  gravity_only.strength = 0.0;
  if (!(target.gravity > 0.0)) {
    throw InputError("the gravity-regime limit needs gravity > 0 (got " + format_number(target.gravity) +
                     ")");
  }
  return crater_radius(law, impactor, gravity_only);
}

double strength_limit_radius(const ScalingLaw& law, const Impactor& impactor, const Target& target) {
  Target strength_only = target;
  strength_only.gravity = 0.0;
  if (!(target.strength > 0.0)) {
    throw InputError("the strength-regime limit needs strength > 0 (got " + format_number(target.strength) +
                     ")");
  }
  return crater_radius(law, impactor, strength_only);
}

std::string to_string(RegimeKind kind) {
  switch (kind) {
    case RegimeKind::gravity:
      return "gravity";
    case RegimeKind::strength:
      return "strength";
    case RegimeKind::transitional:
      break;
  }
  return "transitional";
}

Regime regime(const ScalingLaw& law, const Impactor& impactor, const Target& target) {
  check_inputs(impactor, target);
  const PiGroups pi = pi_groups(impactor, target);
  check_needed_constants(law, pi);
  Regime out;
  if (!(pi.pi3 > 0.0)) {
    out.gravity_share = 1.0;
  } else if (!(pi.pi2 > 0.0)) {
    out.strength_share = 1.0;
  } else {
    const ScalingLaw holsapple = convert(law, Form::holsapple);
    double ln_g = 0.0;
    double ln_s = 0.0;
    detail::holsapple_terms(std::log(holsapple.coefficient_2), law.mu, law.nu, log_pi_groups(pi), ln_g, ln_s);
    // share of the gravity term = 1 / (1 + e^(ln_s - ln_g)), written to stay finite for any difference.
    out.gravity_share = 1.0 / (1.0 + std::exp(std::min(ln_s - ln_g, 700.0)));
    out.strength_share = 1.0 / (1.0 + std::exp(std::min(ln_g - ln_s, 700.0)));
  }
  if (out.gravity_share >= 0.9) {
    out.kind = RegimeKind::gravity;
  } else if (out.strength_share >= 0.9) {
    out.kind = RegimeKind::strength;
  } else {
    out.kind = RegimeKind::transitional;
  }
  return out;
}

}  // namespace craterkit::scaling
