#pragma once
// Tillotson equation of state for solids under shock (Tillotson 1962, General Atomic report GA-3216;
// Melosh 1989, "Impact Cratering", appendix II; parameters of Benz & Asphaug 1999), as stated in
// docs/physics.md section 2. eta = rho/rho0, chi = eta - 1, E specific internal energy, and
// omega = E / (E0 eta^2) + 1.
//
// Branches:
//  - compressed, rho >= rho0 (any E):
//      P_c = [a + b/omega] rho E + A chi + B chi^2
//  - cold expanded, rho < rho0 and E <= E_iv: the same form WITHOUT the B chi^2 term (our choice):
//      P_c = [a + b/omega] rho E + A chi
//    B is fitted to the curvature of compression data and has no meaning in tension; kept, it turns
//    the cold bulk modulus rho dP/drho = rho (A + 2 B chi)/rho0 negative below eta = 1 - A/(2B)
//    (0.5 for basalt, 0.42 for aluminium), an unstable state with c^2 < 0. Dropping it changes
//    neither P nor dP/drho at rho0 (d(B chi^2)/dchi = 0 at chi = 0), so P and c stay continuous.
//  - hot expanded, rho < rho0 and E >= E_cv:
//      P_e = a rho E + [b rho E/omega + A chi exp(-beta z)] exp(-alpha z^2),  z = rho0/rho - 1
//  - in between, rho < rho0 and E_iv < E < E_cv: linear in E between the two,
//      P = [(E - E_iv) P_e + (E_cv - E) P_c] / (E_cv - E_iv)   (P_c the cold-expanded form above).
//
// Sound speed: c^2 = dP/drho|_E + (P/rho^2) dP/dE with the analytic derivatives of the branch in use,
// floored at c_min = min_sound_speed_fraction * sqrt(A/rho0) (c^2 can turn negative in expansion and
// is undefined in the mixed branch's kinks; the floor keeps the time step and viscosity defined).
// P is continuous everywhere; dP/drho and c are continuous across rho = rho0; dP/dE (hence c) jumps
// at E = E_iv and E = E_cv in expansion, a property of the Tillotson interpolation itself.
//
// Negative specific energy: the law is written for E >= 0 (E = 0 is the cold state), and its thermal
// factor b/omega has a pole at E = -E0 eta^2 (-5 MJ/kg for aluminium at rho0), where P jumps from -inf
// to +inf. E < 0 is not physical (the work of a reversible cycle about rho0 is >= 0) but a particle can
// reach it numerically: the energy equation is not adiabatic where neighbour masses differ (rates.hpp),
// and the particles of a light projectile stand-in ringing against a heavier target fell below -5 MJ/kg
// within 0.2 ms, crossed the pole and exploded (docs/validation.md, "The stand-in on the graded
// target"). So E < 0 is read as the cold state E = 0 (the thermal terms vanish, dP/dE = 0); P stays
// continuous at E = 0. The particle keeps its E (the energy budget still sums it).
// Precondition (the caller's; no check in the hot path): density > 0 (density <= 0 returns P = 0
// and c = c_min).
#include <algorithm>
#include <cmath>

#include "craterkit/sph/physics/eos_state.hpp"

namespace craterkit::sph {

struct Tillotson {
  double reference_density;                // rho0, kg/m^3
  double A;                                // Pa
  double B;                                // Pa
  double E0;                               // J/kg
  double E_iv;                             // energy of incipient vaporisation, J/kg
  double E_cv;                             // energy of complete vaporisation, J/kg
  double a;                                // dimensionless
  double b;                                // dimensionless
  double alpha;                            // alpha_T of docs/physics.md, dimensionless
  double beta;                             // dimensionless
  double min_sound_speed_fraction = 0.01;  // c_min / sqrt(A/rho0)
};

namespace tillotson_detail {

struct Branch {
  double pressure, dp_ddensity, dp_denergy;
};

// [a + b/omega] rho E + A chi (+ B chi^2 when with_b). With q = E/(E0 eta^2), omega = q + 1:
// d/dE = rho (a + b/omega^2); d/drho = (a + b/omega) E + 2 b E q/omega^2 + (A + 2 B chi)/rho0.
inline Branch compressed(const Tillotson& m, double rho, double e, bool with_b) noexcept {
  const double eta = rho / m.reference_density;
  const double chi = eta - 1.0;
  const double q = e / (m.E0 * eta * eta);
  const double omega = q + 1.0;
  const double b_chi = with_b ? m.B * chi : 0.0;
  const double thermal = m.a + m.b / omega;
  return Branch{thermal * rho * e + m.A * chi + b_chi * chi,
                thermal * e + 2.0 * m.b * e * q / (omega * omega) + (m.A + 2.0 * b_chi) / m.reference_density,
                rho * (m.a + m.b / (omega * omega))};
}

// a rho E + [b rho E/omega + A chi exp(-beta z)] exp(-alpha z^2), z = rho0/rho - 1, dz/drho = -rho0/rho^2.
inline Branch expanded(const Tillotson& m, double rho, double e) noexcept {
  const double rho0 = m.reference_density;
  const double eta = rho / rho0;
  const double chi = eta - 1.0;
  const double q = e / (m.E0 * eta * eta);
  const double omega = q + 1.0;
  const double z = rho0 / rho - 1.0;
  const double dz_drho = -rho0 / (rho * rho);
  const double decay_alpha = std::exp(-m.alpha * z * z);
  // Far expanded (z > ~12 for alpha = 5) only the gas term a rho E is left; returning it here also
  // avoids 0 * inf in the derivatives at extreme expansion.
  if (decay_alpha == 0.0) return Branch{m.a * rho * e, m.a * e, m.a * rho};
  const double decay_beta = std::exp(-m.beta * z);
  const double bracket = m.b * rho * e / omega + m.A * chi * decay_beta;
  const double dbracket_drho = m.b * e / omega + 2.0 * m.b * e * q / (omega * omega) +
                               m.A * decay_beta / rho0 - m.A * chi * m.beta * decay_beta * dz_drho;
  const double ddecay_alpha_drho = -2.0 * m.alpha * z * dz_drho * decay_alpha;
  return Branch{m.a * rho * e + bracket * decay_alpha,
                m.a * e + dbracket_drho * decay_alpha + bracket * ddecay_alpha_drho,
                rho * (m.a + m.b * decay_alpha / (omega * omega))};
}

inline Branch branch(const Tillotson& m, double rho, double e) noexcept {
  if (e < 0.0) {
    const Branch cold = compressed(m, rho, 0.0, rho >= m.reference_density);
    return Branch{cold.pressure, cold.dp_ddensity, 0.0};
  }
  if (rho >= m.reference_density) return compressed(m, rho, e, true);
  if (e <= m.E_iv) return compressed(m, rho, e, false);
  if (e >= m.E_cv) return expanded(m, rho, e);
  // Mixed: P = [(E - E_iv) P_e + (E_cv - E) P_c] / (E_cv - E_iv); d/dE also differentiates the weights.
  const Branch cold = compressed(m, rho, e, false);
  const Branch hot = expanded(m, rho, e);
  const double width = m.E_cv - m.E_iv;
  const double w_hot = (e - m.E_iv) / width;
  const double w_cold = (m.E_cv - e) / width;
  return Branch{w_hot * hot.pressure + w_cold * cold.pressure,
                w_hot * hot.dp_ddensity + w_cold * cold.dp_ddensity,
                w_hot * hot.dp_denergy + w_cold * cold.dp_denergy + (hot.pressure - cold.pressure) / width};
}

}  // namespace tillotson_detail

// Bulk sound speed of the unshocked material, sqrt(A/rho0), m/s.
inline double reference_sound_speed(const Tillotson& m) noexcept {
  return std::sqrt(m.A / m.reference_density);
}

inline EosState evaluate(const Tillotson& m, double density, double specific_energy) noexcept {
  const double c2_min = m.min_sound_speed_fraction * m.min_sound_speed_fraction * m.A / m.reference_density;
  if (!(density > 0.0)) return EosState{0.0, std::sqrt(c2_min), 0.0, 0.0};
  const auto s = tillotson_detail::branch(m, density, specific_energy);
  const double c2 = s.dp_ddensity + s.pressure / (density * density) * s.dp_denergy;
  return EosState{s.pressure, std::sqrt(std::max(c2, c2_min)), s.dp_ddensity, s.dp_denergy};
}

}  // namespace craterkit::sph
