#pragma once
// Lithostatic initial state of an impact target (docs/physics.md section 4): at rest under constant gravity g
// with S = 0 and specific internal energy E = 0, the bulk pressure obeys dP/d(depth) = rho(P) g, where the
// bulk density rho(P) follows from the material's equation of state at E = 0:
//   non-porous:  P_m(rho, 0) = P                          -> rho
//   porous (P-alpha):  P = P_m(alpha rho, 0) / alpha with alpha = alpha_c(P), the crush curve
//                      (alpha = alpha0 for P <= P_e, i.e. everywhere in a metre-to-100-m target under
//                      milligravity; deeper, the state lies on the virgin crush curve, as if it had been
//                      loaded slowly from zero).
// E = 0 is the cold state the Tillotson law is built around; it is also the energy of the impact set-up's
// projectile, so no thermal term has to be balanced.
#include <stdexcept>

#include "craterkit/sph/physics/material.hpp"

namespace craterkit::impact {

struct LithostaticState {
  double density;     // bulk density rho, kg/m^3
  double distention;  // alpha (1 for a non-porous material)
};

// The bulk density and distention of `material` at bulk pressure P >= 0 and E = 0. The matrix density is
// the root of P_m(rho_m, 0) = alpha P, bracketed above the reference density and found by the Brent (GSL)
// false-position method to a relative 1e-15. Throws craterkit::InputError (naming the material) if the
// law has no cold pressure (an ideal gas) or no root is found.
LithostaticState lithostatic_state(const sph::Material& material, double pressure);

// The pressure after descending `thickness` (m) through `material` under gravity g (m/s^2, >= 0), from
// pressure p_top: dP/dd = g rho(P), integrated by the classical fourth-order Runge-Kutta method with
// `substeps` equal steps (rho(P) is smooth and, below P_e, nearly constant, so a few steps per
// particle layer reach round-off).
double lithostatic_pressure_after(const sph::Material& material, double p_top, double thickness, double g,
                                  int substeps = 2);

// As lithostatic_pressure_after, with the step chosen by step doubling: one RK4 step over the whole
// thickness is accepted when two half steps agree with it to relative_tolerance, otherwise each half is
// integrated the same way (to at most 2^30 pieces). Under milligravity rho(P) is constant to ~1e-10
// (P / bulk modulus), so one step is exact to rounding however long the column; through the crush curve
// the steps shrink where rho(P) bends. For the graded target, where every particle has its own column.
double lithostatic_pressure_adaptive(const sph::Material& material, double p_top, double thickness, double g,
                                     double relative_tolerance = 1e-13);

}  // namespace craterkit::impact
