#pragma once
// Per-particle thermodynamic state before the pair pass: pressure and sound speed from each
// particle's equation of state (eos.hpp), and 1/rho and m/rho for the pair pass.
// The material is resolved here, once per particle (std::visit over the EquationOfState variant),
// never inside the pair loop.
#include <span>

#include "craterkit/sph/physics/eos.hpp"
#include "craterkit/sph/particles/particles.hpp"
#include "craterkit/sph/rates/rates.hpp"

namespace craterkit::sph {

// equations_of_state[m] is the law of material id m. Fixed particles are evaluated too (they
// exert pressure on their neighbours). Throws std::out_of_range for a material id without a law.
void update_pressure(Particles& particles, std::span<const EquationOfState> equations_of_state,
                     RateWorkspace& workspace, const ParticleSelection& selection);

}  // namespace craterkit::sph
