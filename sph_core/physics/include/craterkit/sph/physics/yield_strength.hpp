#pragma once
// Yield strength of the target, boulders and projectile (docs/physics.md section 2, "Strength").
//
// Lundborg (1967) pressure-dependent yield, in the form of Collins, Melosh & Ivanov (2004, eq. 4):
//   Y(P) = Y0 + f P / (1 + f P / (Y_dm - Y0))          for P >= 0,
// extended linearly into tension (docs/physics.md): Y(P) = max(0, Y0 + f P) for P < 0, which reaches zero
// at the tensile strength P = -Y0/f. Independently the pressure is floored at
//   P_min = -Y0 min(1, 1/f),
// whichever limit is reached first. Both use the current, strain-weakened cohesion (below), so a
// cohesionless material carries no tension at all. Y is compared with sqrt(J2) (not sqrt(3 J2)).
#include <algorithm>
#include <cmath>

namespace craterkit::sph {

// The strain that weakens the cohesion (docs/strength_and_porosity.md, "Which strain weakens"):
//  - total: the accumulated total deviatoric strain, elastic and plastic (docs/physics.md section 2; the
//    published model and the default);
//  - plastic_after_switch: the total strain in the shock stage, only the plastic strain after the late-stage
//    switch, whose shear modulus (scaled by A_low/A, about 1e-6 for rock) turns every stress of the slow flow
//    into an elastic strain about 1e6 times the shock stage's, which the total strain would count;
//  - plastic: the plastic strain only. late_stage_material() turns plastic_after_switch into plastic.
enum class WeakeningStrain { total, plastic_after_switch, plastic };

struct LundborgStrength {
  double cohesion = 0.0;              // Y0, Pa (intact, before strain weakening)
  double friction_coefficient = 0.0;  // f, dimensionless
  double limiting_strength = 3.5e9;   // Y_dm, Pa
  WeakeningStrain weakening_strain = WeakeningStrain::total;
};

struct VonMisesStrength {
  double yield_strength = 0.0;  // Y, Pa, independent of pressure
};

// Friction coefficient from an angle of repose theta (Luther et al. 2022):
// f = 2 sqrt(2) sin(theta) / (3 - sin(theta)); 30 deg gives f ~ 0.566.
inline double friction_from_repose_angle(double repose_angle_radians) noexcept {
  const double s = std::sin(repose_angle_radians);
  return 2.0 * std::sqrt(2.0) * s / (3.0 - s);
}

// Its inverse, sin(theta) = 3 f / (2 sqrt(2) + f), in radians; defined for 0 <= f < sqrt(2).
inline double repose_angle_from_friction(double friction) noexcept {
  return std::asin(3.0 * friction / (2.0 * std::sqrt(2.0) + friction));
}

// Strain weakening (docs/physics.md; cf. Collins et al. 2008): cohesion falls linearly with the accumulated
// total strain and is lost at total_strain >= 1.
inline double weakened_cohesion(double cohesion, double total_strain) noexcept {
  return cohesion * std::max(0.0, 1.0 - total_strain);
}

// Y(P) for the Lundborg law with a given (already weakened) cohesion Y0.
inline double lundborg_yield_strength(const LundborgStrength& law, double cohesion,
                                      double pressure) noexcept {
  const double f = law.friction_coefficient;
  if (pressure >= 0.0) {
    const double span = law.limiting_strength - cohesion;  // > 0 by validation (Y_dm > Y0)
    return cohesion + f * pressure / (1.0 + f * pressure / span);
  }
  return std::max(0.0, cohesion + f * pressure);
}

// The most negative pressure the material can hold: -Y0 min(1, 1/f); zero without cohesion.
inline double lundborg_pressure_floor(const LundborgStrength& law, double cohesion) noexcept {
  const double f = law.friction_coefficient;
  const double limit = (f > 1.0) ? 1.0 / f : 1.0;
  return -cohesion * limit;
}

}  // namespace craterkit::sph
