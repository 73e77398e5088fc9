#pragma once
// Point-source crater scaling (Holsapple 1993; Housen & Holsapple 2011), docs/physics.md section 6.
//
// Two parameterisations of the same function are supported; published constants only make sense
// in their own form:
//   Holsapple (1993):
//     pi_R = K1 { pi2 pi4^((6nu-2-mu)/(3mu)) + [K2 pi3 pi4^((6nu-2)/(3mu))]^((2+mu)/2) }^(-mu/(2+mu))
//   Housen & Holsapple (2011):
//     pi_R = H1 pi4^((2+mu-6nu)/(3(2+mu))) { pi2 + (H1/H2)^((2+mu)/mu) pi4^nu pi3^((2+mu)/2) }^(-mu/(2+mu))
// with K1 = H1 and K2 = (H1/H2)^(2/mu). R is the apparent crater radius at the pre-impact level.
// All quantities SI.
#include <string>

namespace craterkit::scaling {

enum class Form {
  holsapple,  // constants K1, K2
  hh2011,     // constants H1, H2 (Housen & Holsapple 2011)
};

std::string to_string(Form form);                    // "holsapple" | "hh2011"
Form form_from_string(const std::string&);           // throws InputError naming the allowed values
std::string coefficient_name(Form form, int which);  // which = 1 or 2: "K1"/"K2" or "H1"/"H2"

// One constant set. coefficient_1/2 are K1/K2 in the Holsapple form and H1/H2 in the HH2011 form.
struct ScalingLaw {
  Form form = Form::hh2011;
  double coefficient_1 = 0.0;  // K1 or H1
  double coefficient_2 = 0.0;  // K2 or H2
  double mu = 0.0;             // velocity exponent, 1/3 (momentum) .. 2/3 (energy)
  double nu = 0.0;             // density exponent, about 0.4
};

// Exact conversion between the forms (K1 = H1, K2 = (H1/H2)^(2/mu)); identity if already in `to`.
ScalingLaw convert(const ScalingLaw& law, Form to);

struct Impactor {
  double radius = 0.0;    // a, m
  double density = 0.0;   // delta, kg/m^3
  double velocity = 0.0;  // U, m/s (normal component for oblique impacts)
};

struct Target {
  double density = 0.0;   // rho, bulk, kg/m^3
  double gravity = 0.0;   // g, m/s^2
  double strength = 0.0;  // Y, Pa (cohesion-like strength of the scaling law)
};

struct PiGroups {
  double pi2 = 0.0;  // g a / U^2
  double pi3 = 0.0;  // Y / (rho U^2)
  double pi4 = 0.0;  // rho / delta
};

PiGroups pi_groups(const Impactor& impactor, const Target& target);

double impactor_mass(const Impactor& impactor);  // 4/3 pi a^3 delta

// pi_R = R (rho/m)^(1/3).
double pi_R(const ScalingLaw& law, const PiGroups& pi);

// Apparent crater radius R, m.
double crater_radius(const ScalingLaw& law, const Impactor& impactor, const Target& target);

// R/a = pi_R (3 rho / (4 pi delta))^(-1/3).
double radius_ratio(const ScalingLaw& law, const Impactor& impactor, const Target& target);

// Pure limits: the same law with only the gravity term (strength = 0) or only the strength term.
double gravity_limit_radius(const ScalingLaw& law, const Impactor& impactor, const Target& target);
double strength_limit_radius(const ScalingLaw& law, const Impactor& impactor, const Target& target);

enum class RegimeKind { gravity, strength, transitional };
std::string to_string(RegimeKind kind);  // "gravity" | "strength" | "transitional"

// Which term of the braces dominates. gravity_share + strength_share = 1; each is that term's share
// of the sum inside the braces. kind is gravity (strength) when that share is >= 0.9, else transitional.
struct Regime {
  RegimeKind kind = RegimeKind::transitional;
  double gravity_share = 0.0;
  double strength_share = 0.0;
};
Regime regime(const ScalingLaw& law, const Impactor& impactor, const Target& target);

// Inverse problems (GSL root finding with bracketing). Throw craterkit::InputError with a message
// that says why when no solution exists (e.g. a crater radius the law cannot produce at this speed).
// impactor.radius is ignored by solve_impactor_radius; impactor.velocity by solve_velocity; target.strength
// by solve_strength, which needs a crater radius below the impact's gravity-regime (Y = 0) radius.
double solve_impactor_radius(const ScalingLaw& law, double crater_radius, const Impactor& impactor,
                             const Target& target);
double solve_velocity(const ScalingLaw& law, double crater_radius, const Impactor& impactor,
                      const Target& target);
double solve_strength(const ScalingLaw& law, double crater_radius, const Impactor& impactor,
                      const Target& target);

// Throws InputError unless both coefficients > 0, mu > 0 and nu >= 0 (the fit, not this check,
// enforces 1/3 <= mu <= 2/3); the message names the constant, its value and the allowed range.
void validate(const ScalingLaw& law);

}  // namespace craterkit::scaling
