#pragma once
// The point-source law of docs/physics.md section 6 in log space, templated so that the Ceres fit can
// differentiate it automatically (T = ceres::Jet) and the forward model uses the very same code
// (T = double). Private to the scaling library.
//
// Each form is evaluated as written in its own paper (no conversion), so that the test of the
// identity K1 = H1, K2 = (H1/H2)^(2/mu) compares two independent evaluations.
//   Holsapple (1993):
//     ln pi_R = ln K1 - mu/(2+mu) ln{ pi2 pi4^((6nu-2-mu)/(3mu)) + [K2 pi3 pi4^((6nu-2)/(3mu))]^((2+mu)/2) }
//   Housen & Holsapple (2011):
//     ln pi_R = ln H1 + (2+mu-6nu)/(3(2+mu)) ln pi4
//               - mu/(2+mu) ln{ pi2 + (H1/H2)^((2+mu)/mu) pi4^nu pi3^((2+mu)/2) }
// A term whose pi-group is zero (g = 0 or Y = 0) is left out rather than evaluated as exp(-inf), so
// that a constant the other term alone needs (e.g. H2 of a gravity-regime set) is never touched. With
// pi2 = 0 the HH2011 form is evaluated as its exact strength limit H2 pi3^(-mu/2) pi4^((1-3nu)/3),
// which is the same expression with H1 cancelled analytically.
#include <algorithm>
#include <cmath>

#include "craterkit/scaling/point_source.hpp"

namespace craterkit::scaling::detail {

// ln(e^x + e^y) without overflow.
template <typename T>
T log_add_exp(const T& x, const T& y) {
  using std::exp;
  using std::log1p;
  if (x > y) return x + log1p(exp(y - x));
  return y + log1p(exp(x - y));
}

// Log-space pi groups; has_gravity / has_strength say whether pi2 / pi3 is non-zero.
template <typename T>
struct LogPiGroups {
  T ln_pi2{};
  T ln_pi3{};
  T ln_pi4{};
  bool has_gravity = true;
  bool has_strength = true;
};

// Natural logs of the two terms inside the braces of the Holsapple form (shared by both forms: the
// HH2011 braces are the Holsapple braces times pi4^(-(6nu-2-mu)/(3mu)), which does not change the share
// of each term). Callers leave out a term whose pi-group is zero.
template <typename T>
void holsapple_terms(const T& ln_K2, const T& mu, const T& nu, const LogPiGroups<T>& pi, T& ln_gravity_term,
                     T& ln_strength_term) {
  ln_gravity_term = pi.ln_pi2 + (6.0 * nu - 2.0 - mu) / (3.0 * mu) * pi.ln_pi4;
  ln_strength_term = (2.0 + mu) / 2.0 * (ln_K2 + pi.ln_pi3 + (6.0 * nu - 2.0) / (3.0 * mu) * pi.ln_pi4);
}

// ln pi_R. ln_c1, ln_c2 are ln K1, ln K2 (Holsapple) or ln H1, ln H2 (HH2011).
template <typename T>
T log_pi_R(Form form, const T& ln_c1, const T& ln_c2, const T& mu, const T& nu, const LogPiGroups<T>& pi) {
  const T shrink = mu / (2.0 + mu);
  if (form == Form::holsapple) {
    T ln_g, ln_s;
    holsapple_terms(ln_c2, mu, nu, pi, ln_g, ln_s);
    T ln_braces;
    if (pi.has_gravity && pi.has_strength) {
      ln_braces = log_add_exp(ln_g, ln_s);
    } else if (pi.has_gravity) {
      ln_braces = ln_g;
    } else {
      ln_braces = ln_s;
    }
    return ln_c1 - shrink * ln_braces;
  }
  // Housen & Holsapple (2011).
  if (!pi.has_gravity) {
    return ln_c2 - mu / 2.0 * pi.ln_pi3 + (1.0 - 3.0 * nu) / 3.0 * pi.ln_pi4;
  }
  const T ln_g = pi.ln_pi2;
  T ln_braces = ln_g;
  if (pi.has_strength) {
    const T ln_s = (2.0 + mu) / mu * (ln_c1 - ln_c2) + nu * pi.ln_pi4 + (2.0 + mu) / 2.0 * pi.ln_pi3;
    ln_braces = log_add_exp(ln_g, ln_s);
  }
  return ln_c1 + (2.0 + mu - 6.0 * nu) / (3.0 * (2.0 + mu)) * pi.ln_pi4 - shrink * ln_braces;
}

}  // namespace craterkit::scaling::detail
