#include "craterkit/sph/physics/late_stage.hpp"

#include <cmath>
#include <sstream>
#include <string>
#include <variant>

#include "craterkit/common/input_error.hpp"

namespace craterkit::sph {

Material late_stage_material(const Material& material, double A_low, bool tensile_porosity) {
  if (!(A_low > 0.0) || !std::isfinite(A_low)) {
    std::ostringstream text;
    text.precision(17);
    text << "late-stage transition: A_low = " << A_low << " is out of range: must be > 0 (Pa)";
    throw InputError(text.str());
  }
  const auto reference = solid_reference(material.eos);
  if (!reference) {
    throw InputError("late-stage transition: material '" + material.name +
                     "' has an ideal-gas equation of state, which has no bulk modulus A to scale from "
                     "(the transition applies to solid materials: tillotson or low_sound_speed)");
  }
  const double stiffness_factor = A_low / reference->bulk_modulus;  // A_low / A
  const double speed_factor = std::sqrt(stiffness_factor);          // every sound speed scales by this

  Material out = material;
  out.eos = LowSoundSpeed{reference->density, A_low};
  out.shear_modulus = material.shear_modulus * stiffness_factor;
  if (out.strength) {
    auto* law = std::get_if<LundborgStrength>(&*out.strength);
    if (law != nullptr && law->weakening_strain == WeakeningStrain::plastic_after_switch)
      law->weakening_strain = WeakeningStrain::plastic;
  }
  if (out.porosity) {
    out.porosity->porous_sound_speed *= speed_factor;
    // Exactly sqrt(A_low/rho0), the reference sound speed of the new law (not a rounded product).
    out.porosity->matrix_sound_speed = std::sqrt(A_low / reference->density);
    out.porosity->opens_in_tension = tensile_porosity;
  }
  std::ostringstream text;
  text.precision(6);
  text << " [late stage: linear law, A_low = " << A_low << " Pa, G scaled by " << stiffness_factor
       << (out.porosity && tensile_porosity ? ", tensile porosity" : "") << "]";
  out.description += text.str();
  return out;
}

std::vector<Material> late_stage_materials(std::span<const Material> materials, double A_low) {
  std::vector<Material> out;
  out.reserve(materials.size());
  for (const auto& m : materials) out.push_back(late_stage_material(m, A_low));
  return out;
}

}  // namespace craterkit::sph
