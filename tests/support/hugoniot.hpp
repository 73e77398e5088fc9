#pragma once
// Shock (Hugoniot) states of any craterkit equation of state and the impedance match of two plates,
// by root finding (GSL Brent) on the Rankine-Hugoniot jump conditions for a shock into material at
// rest in the state (rho1, E1, P1 = P(rho1, E1)):
//   mass      rho1 U_s = rho (U_s - u_p)
//   momentum  P - P1 = rho1 U_s u_p
//   energy    E - E1 = (P + P1)/2 (1/rho1 - 1/rho)
// so that u_p = sqrt((P - P1)(1/rho1 - 1/rho)) and U_s = rho u_p / (rho - rho1).
#include "craterkit/sph/physics/eos.hpp"

namespace craterkit::test_support {

struct InitialState {
  double density;
  double specific_energy = 0.0;
};

struct HugoniotPoint {
  double density;
  double specific_energy;
  double pressure;
  double particle_velocity;  // jump in material velocity across the shock, m/s
  double shock_velocity;     // relative to the unshocked material, m/s
};

// The shocked state at density rho > rho1: solves the energy jump for E (P(rho, E) from the EOS).
// Throws std::domain_error when no shocked state exists at that density (beyond maximum compression).
HugoniotPoint hugoniot_at_density(const sph::EquationOfState& eos, const InitialState& initial,
                                  double density);

// The shocked state with particle velocity u_p >= 0 (nested root: density from u_p, energy from density).
HugoniotPoint hugoniot_at_particle_velocity(const sph::EquationOfState& eos, const InitialState& initial,
                                            double particle_velocity);

struct ImpedanceMatch {
  double pressure;           // at the contact, both sides
  double particle_velocity;  // of the contact in the target's rest frame
  HugoniotPoint projectile;  // shocked projectile (particle_velocity = impact_speed - contact velocity)
  HugoniotPoint target;      // shocked target
};

// A flat projectile plate hits a target plate at rest at impact_speed > 0; both shocks are steady.
// Equal pressure and velocity at the contact: P_target(u) = P_projectile(impact_speed - u).
ImpedanceMatch impedance_match(const sph::EquationOfState& projectile, const InitialState& projectile_initial,
                               const sph::EquationOfState& target, const InitialState& target_initial,
                               double impact_speed);

}  // namespace craterkit::test_support
