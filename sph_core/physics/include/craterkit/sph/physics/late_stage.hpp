#pragma once
// Late-stage transition to a low-sound-speed medium (Raducan et al. 2022; docs/physics.md section 3).
// At t_transition every material's matrix equation of state is replaced by the energy-free linear law
// P_m = A_low (rho_m/rho_m0 - 1) (low_sound_speed.hpp) with the same reference density rho_m0, and its
// shear modulus is scaled by the same factor A_low/A (A the bulk modulus of the law it replaces), which
// keeps Poisson's ratio. Sound speeds and the shear part of the signal speed scale by sqrt(A_low/A), so
// the time step grows by sqrt(A/A_low).
//
// What is kept (docs/materials.md, "Late-stage transition"):
//  - [strength] unchanged: cohesion, friction and limiting strength are properties of the granular
//    material, not of the wave speed. A material with weakening_strain = "plastic_after_switch" counts
//    only the plastic strain from here on (yield_strength.hpp, WeakeningStrain).
//  - [porosity]: the crush curve is unchanged and keeps working with the linear matrix law
//    (distention_rate() gets dP_m/drho_m = A_low/rho_m0, dP_m/dE = 0); both sound speeds of the
//    porous interpolation (c_e and c_s) are scaled by sqrt(A_low/A), so h(alpha) and the reduced shear
//    modulus rule are the same functions of alpha as before. In practice the bulk pressure of the slow
//    late-stage flow stays far below the elastic limit P_e (for the nominal target P_e/A_low ~ 37 at
//    A_low = 0.027 MPa), so the distention is frozen after the switch: compaction happens in the shock.
//    With `tensile_porosity` a porous material's matrix no longer holds tension: material loosened by the
//    excavation opens pores (PAlphaPorosity::opens_in_tension) and carries load as soon as it is pressed.
#include <span>
#include <vector>

#include "craterkit/sph/physics/material.hpp"

namespace craterkit::sph {

// The material after the switch. Throws craterkit::InputError when A_low is not > 0 or the material has
// no bulk modulus to scale from (an ideal gas), naming the material.
Material late_stage_material(const Material& material, double A_low, bool tensile_porosity = false);

// The whole material table (index = material id), switched.
std::vector<Material> late_stage_materials(std::span<const Material> materials, double A_low);

}  // namespace craterkit::sph
