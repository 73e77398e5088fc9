#pragma once
// Solid mechanics per particle (physics.md section 2, "Strength"), the two halves around the pair pass:
//  - update_material_state(): before the pair pass, for runs with at least one [strength] material.
//    Bulk pressure (with the strength model's floor), the longitudinal signal speed
//    c_L = sqrt(c^2 + 4/3 G/rho) (physics.md section 1) in Particles::sound_speed, so that the Courant
//    step and the viscosity see the fastest elastic wave, the shear modulus G, and the radial return of
//    the deviatoric stress onto the yield surface of the current state (deviatoric_stress.hpp). Calling
//    it after each update of the stress (predict and correct) is the "radial return after each step".
//  - compute_stress_rates(): after the pair pass, the Jaumann rate dS/dt of Hooke's law with the
//    Randles-Libersky corrected velocity gradient, and the rate of the accumulated strain
//    sqrt(eps_dot':eps_dot'/2), stored in Particles for the integrator.
// Not yet done: the P-alpha distention update (porous materials are evaluated at their current,
// frozen, distention; c_L then uses the matrix sound speed, which is the elastic wave speed while
// alpha is frozen, material_response.hpp).
#include <span>
#include <vector>

#include "craterkit/sph/material.hpp"
#include "craterkit/sph/particles.hpp"
#include "craterkit/sph/rates.hpp"

namespace craterkit::sph {

// materials[m] is material id m. Fills pressure, sound_speed (c_L), workspace.inverse_density and
// volume like update_pressure(), and shear_modulus[i] (resized); applies the radial return to the
// stress of every particle. Throws std::out_of_range for a material id without a material.
void update_material_state(Particles& particles, std::span<const Material> materials,
                           RateWorkspace& workspace, std::vector<double>& shear_modulus);

// dS/dt and d(total strain)/dt of every active particle from the corrected gradient of the last rate
// pass (zero for fixed and ejected particles, and no strain accumulates where G = 0).
void compute_stress_rates(Particles& particles, const VelocityGradients& gradients,
                          std::span<const double> shear_modulus);

}  // namespace craterkit::sph
