#pragma once
// Materials: an equation of state, the elastic shear modulus, and optionally a strength model and the
// P-alpha porosity model (read from data/materials/<name>.toml by io/material_file.hpp; schema and
// stated rules in docs/materials.md). Every value is SI. The per-particle evaluation of a material (porous
// pressure and sound speed, reduced shear modulus, yield strength) is in material_response.hpp; the switch to
// the late-stage low-sound-speed medium in late_stage.hpp.
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "craterkit/sph/physics/eos.hpp"
#include "craterkit/sph/physics/p_alpha.hpp"
#include "craterkit/sph/physics/yield_strength.hpp"

namespace craterkit::sph {

// Yield model (docs/physics.md section 2): pressure-dependent Lundborg for the target and boulders,
// constant von Mises for the projectile.
using StrengthModel = std::variant<LundborgStrength, VonMisesStrength>;

// P-alpha porosity (Herrmann 1969; Jutzi et al. 2008): the crush curve, plus the two sound speeds
// between which the elastic sound speed of the porous material is interpolated linearly in alpha
// (Jutzi et al. 2008; rule in material_response.hpp).
struct PAlphaPorosity {
  PAlphaParameters crush_curve;
  double porous_sound_speed = 0.0;  // c_e: bulk sound speed of the cold, unloaded material at alpha0, m/s
  double matrix_sound_speed = 0.0;  // c_s: of the matrix law at its reference state, sqrt(A/rho0), m/s
                                    // (derived from [eos] by the loader, not read from the file)
  // Tensile porosity (late stage only, set by late_stage_material): a matrix stretched below its reference
  // density opens pores instead of holding a tension; update_material_state() raises the distention to
  // rho_m0 / rho, where the matrix pressure is zero (docs/strength_and_porosity.md, "Tensile porosity").
  bool opens_in_tension = false;
};

struct Material {
  std::string name;                        // file stem, e.g. "basalt"
  std::string citation;                    // where the parameters come from
  EquationOfState eos;                     // of the matrix when the material is porous
  double shear_modulus;                    // G, Pa (0 for a fluid); of the matrix when the material is porous
  std::string description;                 // material in words (optional in the file)
  std::optional<StrengthModel> strength;   // none: no deviatoric stress (a fluid)
  std::optional<PAlphaPorosity> porosity;  // none: non-porous (distention 1)
  // Where the values came from, for the run record: the file read (empty when built in code) and a 64-bit
  // hash of its bytes (16 hex digits), with which a resumed run checks that the file did not change.
  std::string source_file;
  std::string source_hash;
};

}  // namespace craterkit::sph
