#pragma once
// Shock (Hugoniot) states of a P-alpha porous material, computed independently of the SPH solver from
// the P-alpha relations (Herrmann 1969; Carroll & Holt 1972; docs/physics.md section 2) and the
// Rankine-Hugoniot jump conditions, for the validation "a shock in the porous target (planar impact)
// reaches the porous Hugoniot state".
//
// Initial state: at rest, cold and unloaded: distention alpha0, bulk density rho1 = rho_m0/alpha0
// (rho_m0 the matrix reference density), E1 = 0, P1 = 0. Final state (bulk rho, E, P, alpha):
//   energy jump    E = (P/2) (1/rho1 - 1/rho)
//   P-alpha        P = P_m(alpha rho, E) / alpha
//   compaction     alpha = alpha_c(P)   (on the crush curve: alpha0 for P <= P_e, 1 for P >= P_s)
//   then           u_p = sqrt(P (1/rho1 - 1/rho)),  U_s = rho u_p / (rho - rho1)  (mass and momentum).
// The state behind the shock is on the crush curve because the pressure rises monotonically through
// the shock while the material compacts (dalpha/dt = (dalpha_c/dP) dP/dt). This is the single-jump
// Hugoniot: the elastic precursor (up to P_e = 1 MPa) that runs ahead of a weak compaction wave is not
// resolved, an error of order P_e/P in the final state.
//
// For a given P, the bulk density is the root of P_m(alpha rho, E(rho))/alpha - P, which rises
// monotonically in rho (dP_m/drho > 0 and dP_m/dE >= 0 with E rising in rho); it is bracketed from
// rho1 (where P_m <= 0) and found by GSL Brent. For a given u_p, P is found by Brent on u_p(P).
#include "craterkit/sph/physics/eos.hpp"
#include "craterkit/sph/physics/p_alpha.hpp"
#include "support/hugoniot.hpp"

namespace craterkit::test_support {

struct PorousHugoniotPoint {
  double bulk_density;       // rho, kg/m^3
  double specific_energy;    // E, J/kg
  double pressure;           // bulk P, Pa
  double distention;         // alpha = alpha_c(P)
  double particle_velocity;  // u_p, m/s
  double shock_velocity;     // U_s relative to the unshocked material, m/s
};

// Bulk density of the unshocked material, rho_m0 / alpha0. Throws std::invalid_argument for a matrix
// without a reference density (an ideal gas).
double porous_initial_density(const sph::EquationOfState& matrix, const sph::PAlphaParameters& crush);

// The shocked state at bulk pressure P > 0.
PorousHugoniotPoint porous_hugoniot_at_pressure(const sph::EquationOfState& matrix,
                                                const sph::PAlphaParameters& crush, double pressure);

// The shocked state with particle velocity u_p > 0.
PorousHugoniotPoint porous_hugoniot_at_particle_velocity(const sph::EquationOfState& matrix,
                                                         const sph::PAlphaParameters& crush,
                                                         double particle_velocity);

struct PorousImpedanceMatch {
  double pressure;             // at the contact, both sides, Pa
  double particle_velocity;    // of the contact in the target's rest frame, m/s
  HugoniotPoint projectile;    // shocked (non-porous) projectile
  PorousHugoniotPoint target;  // shocked porous target
};

// A flat, non-porous projectile plate (its own law, initial state) hits the porous target plate at rest
// at impact_speed > 0: P_target(u) = P_projectile(impact_speed - u), both shocks steady.
PorousImpedanceMatch porous_impedance_match(const sph::EquationOfState& projectile,
                                            const InitialState& projectile_initial,
                                            const sph::EquationOfState& target_matrix,
                                            const sph::PAlphaParameters& target_crush, double impact_speed);

}  // namespace craterkit::test_support
