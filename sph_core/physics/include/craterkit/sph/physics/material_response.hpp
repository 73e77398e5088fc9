#pragma once
// Per-particle evaluation of a material (docs/physics.md section 2): the bulk pressure and sound speed of a
// (possibly porous) material from its matrix equation of state, the shear modulus reduced in porous
// material, and the yield strength and pressure floor for the radial return. Free inline functions,
// called once per particle by the solver's per-particle phase; no allocation, no virtual call.
//
// Stated rules (docs/materials.md, "Per-particle evaluation"):
//  - Bulk pressure (Herrmann 1969; Jutzi et al. 2008):  P = P_m(alpha rho, E) / alpha.
//  - Bulk sound speed: c = h(alpha) c_m(alpha rho, E), with c_m the matrix sound speed at the current
//    matrix state and h the linear interpolation in alpha of Jutzi et al. (2008),
//      h(alpha) = 1 + (alpha - 1) (c_e - c_s) / (c_s (alpha0 - 1)),
//    c_e the porous and c_s the matrix sound speed at the reference state. In the cold, unloaded
//    material (c_m = c_s) this is exactly the linear interpolation in alpha between c_s at alpha = 1
//    and c_e at alpha0; under load c follows the stiffening of the matrix.
//    Caveat: this is the elastic wave speed of Jutzi's model, whose elastic branch
//    dalpha/dP = alpha^2/K_s (1 - 1/h^2) softens the response to exactly h c_s. With alpha frozen below
//    P_e (docs/physics.md; distention_rate() of p_alpha.hpp), P = P_m(alpha rho, E)/alpha has
//    dP/drho|_E = dP_m/drho_m and (P/rho^2) dP/dE = (P_m/rho_m^2) dP_m/dE, so elastic waves travel at
//    c_m, up to 1/h = 2.1 times faster than c at alpha0: the time step should use matrix_sound_speed.
//  - Shear modulus: G(alpha) = G_m h(alpha)^2 / alpha. The bulk modulus of the cold porous material is
//    K = rho c^2 = K_m h^2 / alpha (rho = rho_m0/alpha), so this keeps the matrix's Poisson ratio at every
//    distention, as the late-stage switch does (docs/physics.md section 3). It reduces to G/alpha for
//    c_e = c_s; for c_e << c_s plain G/alpha would give a negative Poisson ratio (G > 3K/2).
//  - Strength: Lundborg with the strain-weakened cohesion, its tension rule and pressure floor
//    (yield_strength.hpp); von Mises constant Y with no pressure floor (the projectile's tension is
//    limited only by its equation of state); no [strength]: a fluid, Y = 0 and G = 0 (no deviatoric
//    stress, and no shear term in the signal speed) and no floor.
//    The floor is applied to the bulk pressure first, the yield strength is evaluated at the floored P.
//  - Plastic compaction: return_to_crush_curve() puts a state left above the crush curve back on it
//    (see there why the rate form of distention_rate() alone is not enough in a shock).
#include <algorithm>
#include <limits>
#include <optional>
#include <type_traits>
#include <variant>

#include "craterkit/sph/physics/eos.hpp"
#include "craterkit/sph/physics/material.hpp"
#include "craterkit/sph/physics/p_alpha.hpp"
#include "craterkit/sph/physics/yield_strength.hpp"

namespace craterkit::sph {

// h(alpha) of Jutzi et al. (2008): the porous-to-matrix sound-speed factor, 1 at alpha = 1 and
// c_e/c_s at alpha0 (h = 1 when alpha0 = 1: nothing to interpolate).
inline double porous_sound_speed_factor(const PAlphaPorosity& porosity, double distention) noexcept {
  const double span = porosity.crush_curve.initial_distention - 1.0;
  if (!(span > 0.0)) return 1.0;
  const double weight = std::clamp((distention - 1.0) / span, 0.0, 1.0);
  return 1.0 + weight * (porosity.porous_sound_speed / porosity.matrix_sound_speed - 1.0);
}

// G(alpha) = G_m h(alpha)^2 / alpha (keeps Poisson's ratio; see the header comment).
inline double porous_shear_modulus(const PAlphaPorosity& porosity, double matrix_shear_modulus,
                                   double distention) noexcept {
  const double h = porous_sound_speed_factor(porosity, distention);
  return matrix_shear_modulus * h * h / distention;
}

// The bulk state of a porous material, and what distention_rate() needs of its matrix.
struct PorousEosState {
  double pressure;            // bulk P = P_m / alpha, Pa
  double sound_speed;         // bulk c = h(alpha) c_m, m/s
  double matrix_sound_speed;  // c_m at the matrix state (alpha rho, E), m/s
  MatrixResponse matrix;      // dP_m/drho_m and dP_m/dE at the matrix state
};

inline PorousEosState evaluate_porous(const EquationOfState& matrix_eos, const PAlphaPorosity& porosity,
                                      double bulk_density, double specific_energy,
                                      double distention) noexcept {
  const EosState m = evaluate(matrix_eos, distention * bulk_density, specific_energy);
  return PorousEosState{m.pressure / distention,
                        porous_sound_speed_factor(porosity, distention) * m.sound_speed, m.sound_speed,
                        MatrixResponse{m.dpressure_ddensity, m.dpressure_denergy}};
}

// Plastic compaction in algebraic form, the P-alpha analogue of the radial return: if the state lies
// above the crush curve, alpha > alpha_c(P) with P = P_m(alpha rho, E)/alpha, returns the distention
// a in [1, alpha] that puts it on the curve, a = alpha_c(P_m(a rho, E)/a), at the same bulk density and
// specific energy; otherwise (elastic, unloading, inside the curve) alpha unchanged. Compaction stays
// irreversible: the result is never above alpha.
// Why: the consistent rate dalpha/dt of distention_rate() moves alpha along the curve by
// (dalpha_c/dP) dP, so it keeps a state on the curve but never brings one back to it. A shock front
// compresses the stiff matrix by ~0.3 % per SPH step, i.e. ~100 MPa of matrix pressure, so the first
// step past P_e leaves the state far above the curve (alpha0 at P ~ 40 MPa, where alpha_c ~ 1.3), an
// error the rate form then carries forever (tests/sph_core/test_porous_shock.cpp: alpha 1.36 instead
// of the Hugoniot's 1.16 behind a 100 m/s piston). Calling this after each update removes it.
// Root of g(a) = a - alpha_c(P(a)), which rises with a, bracketed in [1, alpha]: Illinois false position.
inline double return_to_crush_curve(const EquationOfState& matrix_eos, const PAlphaParameters& crush,
                                    double bulk_density, double specific_energy, double distention) noexcept {
  const auto excess = [&](double a) {
    return a - crush_curve_distention(crush,
                                      evaluate(matrix_eos, a * bulk_density, specific_energy).pressure / a);
  };
  double hi = distention;
  double g_hi = excess(hi);
  if (!(g_hi > 0.0)) return distention;  // on or below the curve
  double lo = 1.0;
  double g_lo = excess(lo);
  if (!(g_lo < 0.0)) return 1.0;  // P >= P_s even when fully compacted
  int side = 0;
  for (int iteration = 0; iteration < 200 && hi - lo > 1e-13 * hi; ++iteration) {
    const double a = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
    const double g = excess(a);
    if (g > 0.0) {
      hi = a;
      g_hi = g;
      if (side == +1) g_lo *= 0.5;  // Illinois: halve the stale end so that both ends converge
      side = +1;
    } else if (g < 0.0) {
      lo = a;
      g_lo = g;
      if (side == -1) g_hi *= 0.5;
      side = -1;
    } else {
      return a;
    }
  }
  return 0.5 * (lo + hi);
}

// Yield strength for the radial return on sqrt(J2), and the lowest bulk pressure the material holds.
struct StrengthState {
  double yield_strength;  // Y, Pa (0: no deviatoric stress)
  double pressure_floor;  // P_min, Pa (-infinity: no floor)
};

inline StrengthState evaluate_strength(const std::optional<StrengthModel>& strength, double pressure,
                                       double total_strain) noexcept {
  constexpr double no_floor = -std::numeric_limits<double>::infinity();
  if (!strength) return StrengthState{0.0, no_floor};
  return std::visit(
      [&](const auto& law) -> StrengthState {
        if constexpr (std::is_same_v<std::decay_t<decltype(law)>, LundborgStrength>) {
          const double cohesion = weakened_cohesion(law.cohesion, total_strain);
          const double floor = lundborg_pressure_floor(law, cohesion);
          return StrengthState{lundborg_yield_strength(law, cohesion, std::max(pressure, floor)), floor};
        } else {
          return StrengthState{law.yield_strength, no_floor};
        }
      },
      *strength);
}

// Everything the per-particle phase needs of a material at one particle.
struct MaterialState {
  double pressure;            // bulk pressure, floored at pressure_floor, Pa
  double sound_speed;         // bulk sound speed (without the shear term of the signal speed), m/s
  double matrix_sound_speed;  // c_m of the matrix state; = sound_speed when non-porous. While alpha is
                              // frozen (elastic regime, p_alpha.hpp) a porous material's pressure
                              // responds with exactly this speed: the time step should use it.
  double shear_modulus;       // G for the Jaumann stress rate and the signal speed (reduced in porous
                              // material; 0 without [strength]), Pa
  double yield_strength;      // Y for radial_return() on sqrt(J2), Pa
  double pressure_floor;      // the floor that was applied, Pa (-infinity: none)
  MatrixResponse matrix;  // for distention_rate(): dP_m/drho_m, dP_m/dE (the law's own for a non-porous one)
};

// density: bulk density; distention: alpha (ignored, i.e. 1, for a non-porous material);
// total_strain: the accumulated strain that weakens the cohesion.
inline MaterialState evaluate_material(const Material& material, double density, double specific_energy,
                                       double distention, double total_strain) noexcept {
  MaterialState out{};
  if (material.porosity) {
    const PorousEosState s =
        evaluate_porous(material.eos, *material.porosity, density, specific_energy, distention);
    out.pressure = s.pressure;
    out.sound_speed = s.sound_speed;
    out.matrix_sound_speed = s.matrix_sound_speed;
    out.matrix = s.matrix;
    out.shear_modulus = porous_shear_modulus(*material.porosity, material.shear_modulus, distention);
  } else {
    const EosState s = evaluate(material.eos, density, specific_energy);
    out.pressure = s.pressure;
    out.sound_speed = s.sound_speed;
    out.matrix_sound_speed = s.sound_speed;
    out.matrix = MatrixResponse{s.dpressure_ddensity, s.dpressure_denergy};
    out.shear_modulus = material.shear_modulus;
  }
  if (!material.strength) out.shear_modulus = 0.0;  // a fluid
  const StrengthState strength = evaluate_strength(material.strength, out.pressure, total_strain);
  out.pressure = std::max(out.pressure, strength.pressure_floor);
  out.yield_strength = strength.yield_strength;
  out.pressure_floor = strength.pressure_floor;
  return out;
}

}  // namespace craterkit::sph
