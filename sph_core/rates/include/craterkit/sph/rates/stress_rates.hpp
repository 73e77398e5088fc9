#pragma once
// Solid mechanics per particle (docs/physics.md section 2, "Strength"), the two halves around the pair pass:
//  - update_material_state(): before the pair pass, for runs with at least one [strength] or
//    [porosity] material (the solid group must be allocated).
//    Bulk pressure (with the strength model's floor), the longitudinal signal speed
//    c_L = sqrt(c^2 + 4/3 G/rho) (docs/physics.md section 1) in Particles::sound_speed, so that the Courant
//    step and the viscosity see the fastest elastic wave, the shear modulus G, and the radial return of
//    the deviatoric stress onto the yield surface of the current state (deviatoric_stress.hpp). Calling
//    it after each update of the stress (predict and correct) is the "radial return after each step".
//  - compute_stress_rates(): after the pair pass, the Jaumann rate dS/dt of Hooke's law with the
//    Randles-Libersky corrected velocity gradient, and the rate of the accumulated strain that weakens the
//    cohesion (yield_strength.hpp, WeakeningStrain): the total sqrt(eps_dot':eps_dot'/2), or for a
//    material counting the plastic strain the plastic rate of a stress on the yield surface (zero below
//    it), stored in Particles for the integrator. The solver has the pair pass store them itself
//    (compute_rates_and_stress_rates, rates.hpp, through store_stress_rate below).
//  - compute_distention_rates(): after the pair pass, the P-alpha distention rate dalpha/dt of
//    Jutzi et al. (2008) (p_alpha.hpp) from the pair pass's drho/dt and du/dt at the same state.
// Porous materials (docs/physics.md section 2, "Porosity"; rules in material_response.hpp):
//  - update_material_state() evaluates P = P_m(alpha rho, E)/alpha and G(alpha) = G_m h^2/alpha, and puts
//    a state left above the crush curve back on it (return_to_crush_curve), the P-alpha analogue of the
//    radial return, after each update of alpha (predict and correct).
//  - Below P_e and on unloading alpha is frozen (docs/physics.md), so the pressure responds with the matrix
//    sound speed c_m: the signal speed for the time step and the viscosity is
//    c_L = sqrt(c_m^2 + 4/3 G(alpha)/rho), the fastest wave the porous material carries (the compaction
//    wave on the crush curve is slower). The reduced bulk sound speed h(alpha) c_m of Jutzi's elastic
//    branch is not used by the solver: it belongs to a reversible elastic dalpha/dP, which docs/physics.md
//    excludes (alpha never increases).
//  - The stress S is the bulk deviatoric stress, evolved with the reduced G(alpha); it is not divided
//    by alpha again in the momentum equation.
// Each function works on the selected particles only (all of them with a global time step, those whose
// step ends now with block time steps) and leaves the others untouched.
#include <cmath>
#include <cstddef>
#include <span>
#include <variant>
#include <vector>

#include "craterkit/sph/particles/particles.hpp"
#include "craterkit/sph/physics/deviatoric_stress.hpp"
#include "craterkit/sph/physics/material.hpp"
#include "craterkit/sph/physics/material_response.hpp"
#include "craterkit/sph/physics/yield_strength.hpp"
#include "craterkit/sph/rates/rates.hpp"

namespace craterkit::sph {

// materials[m] is material id m. Fills pressure, sound_speed (c_L), workspace.inverse_density and
// volume like update_pressure(), and shear_modulus[i] (resized); applies the radial return to the
// stress of every particle and the return to the crush curve to the distention of porous ones. Throws
// std::out_of_range for a material id without a material.
void update_material_state(Particles& particles, std::span<const Material> materials,
                           RateWorkspace& workspace, std::vector<double>& shear_modulus,
                           const ParticleSelection& selection);

// dS/dt and the rate of the weakening strain (Particles::total_strain_rate) of every active particle from
// the corrected gradient of the last rate pass (zero for fixed and ejected particles, and no strain
// accumulates where G = 0). Requires pressure and the returned stress from update_material_state().
void compute_stress_rates(Particles& particles, std::span<const Material> materials,
                          const VelocityGradients& gradients, std::span<const double> shear_modulus,
                          const ParticleSelection& selection);

// What compute_stress_rates() stores for one moving particle i with corrected velocity gradient L
// (L[a][b] = dv_a/dx_b), shear modulus G and material; shared with the pair pass that computes the stress
// rates itself (compute_rates_and_stress_rates), so that both give the same bits. Requires pressure and
// the returned stress from update_material_state().
inline void store_stress_rate(Particles& p, std::size_t i, const Tensor3& L, double G,
                              const Material& material) {
  if (!(G > 0.0)) {
    p.stress_rate_xx[i] = p.stress_rate_xy[i] = p.stress_rate_xz[i] = 0.0;
    p.stress_rate_yy[i] = p.stress_rate_yz[i] = p.total_strain_rate[i] = 0.0;
    return;
  }
  const DeviatoricStress stress{p.stress_xx[i], p.stress_xy[i], p.stress_xz[i], p.stress_yy[i],
                                p.stress_yz[i]};
  const DeviatoricStress rate = jaumann_stress_rate(stress, L, G);
  p.stress_rate_xx[i] = rate.xx;
  p.stress_rate_xy[i] = rate.xy;
  p.stress_rate_xz[i] = rate.xz;
  p.stress_rate_yy[i] = rate.yy;
  p.stress_rate_yz[i] = rate.yz;
  const auto* law = material.strength ? std::get_if<LundborgStrength>(&*material.strength) : nullptr;
  if (law == nullptr || law->weakening_strain != WeakeningStrain::plastic) {
    p.total_strain_rate[i] = deviatoric_strain_rate_invariant(L);
    return;
  }
  // On the yield surface: the stress was returned to it by update_material_state() (to rounding), or is
  // within the 1e-12 that the return leaves alone; the same Y, from the floored pressure and the strain.
  const double yield_strength =
      evaluate_strength(material.strength, p.pressure[i], p.total_strain[i]).yield_strength;
  const bool at_yield = std::sqrt(second_invariant(stress)) >= yield_strength * (1.0 - 1e-9);
  p.total_strain_rate[i] = at_yield ? plastic_strain_rate_at_yield(stress, L) : 0.0;
}

// The per-particle inputs of store_stress_rate() for the pair pass: shear_modulus[i] and materials[id].
struct StressRateInputs {
  const double* shear_modulus;
  const Material* materials;
};

// After the corrector: a porous particle whose distention fell in the step below the crush-curve value of
// its new state (the distention that puts the state reached from alpha^n = distention_before on the
// curve, return_to_crush_curve) is raised to it. Why: the trapezoidal alpha^n + dt/2 (r^n + r^{n+1})
// carries the rate of the step before, so where compaction stops within a step (the back of a shock
// front, the turn from loading to unloading) it compacts up to dt/2 |r^n| too far, an error the model
// can never undo (alpha only decreases). The bound is the backward-Euler (return-mapping) solution of the
// crush-curve constraint; in smooth compaction the trapezoid meets it to O(dt^2).
void limit_compaction(Particles& particles, std::span<const Material> materials,
                      std::span<const double> distention_before, const ParticleSelection& selection);

// dalpha/dt (Particles::distention_rate) of every active porous particle from its current state and the
// drho/dt and du/dt of the last rate pass; zero for non-porous, fixed and ejected particles.
// Requires the solid group (Particles::solid_fields) and pressure from update_material_state().
void compute_distention_rates(Particles& particles, std::span<const Material> materials,
                              const ParticleSelection& selection);

}  // namespace craterkit::sph
