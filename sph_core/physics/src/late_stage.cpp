#include "craterkit/sph/physics/late_stage.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "craterkit/common/input_error.hpp"
#include "craterkit/sph/particles/particles.hpp"

namespace craterkit::sph {

Material late_stage_material(const Material& material, double A_low) {
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
  if (out.porosity) {
    out.porosity->porous_sound_speed *= speed_factor;
    // Exactly sqrt(A_low/rho0), the reference sound speed of the new law (not a rounded product).
    out.porosity->matrix_sound_speed = std::sqrt(A_low / reference->density);
  }
  std::ostringstream text;
  text.precision(6);
  text << " [late stage: linear law, A_low = " << A_low << " Pa, G scaled by " << stiffness_factor << "]";
  out.description += text.str();
  return out;
}

std::vector<Material> late_stage_materials(std::span<const Material> materials, double A_low) {
  std::vector<Material> out;
  out.reserve(materials.size());
  for (const auto& m : materials) out.push_back(late_stage_material(m, A_low));
  return out;
}

MachNumber max_mach_number(std::span<const double> vx, std::span<const double> vy, std::span<const double> vz,
                           std::span<const double> sound_speed, std::span<const std::uint8_t> flags) {
  const std::size_t n = vx.size();
  if (vy.size() != n || vz.size() != n || sound_speed.size() != n || (!flags.empty() && flags.size() != n)) {
    throw std::invalid_argument(
        "max_mach_number: the velocity, sound-speed and flag arrays differ in length");
  }
  MachNumber best{};
  double best_squared = 0.0;  // compare M^2 = v^2/c^2: no square root per particle
#pragma omp parallel
  {
    double local_squared = 0.0;
    std::size_t local_particle = 0;
#pragma omp for nowait schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      if (!flags.empty() && (flags[i] & particle_ejected) != 0) continue;
      const double v2 = vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i];
      if (v2 == 0.0) continue;
      const double c2 = sound_speed[i] * sound_speed[i];
      const double m2 = c2 > 0.0 ? v2 / c2 : std::numeric_limits<double>::infinity();
      if (m2 > local_squared) {
        local_squared = m2;
        local_particle = i;
      }
    }
#pragma omp critical(craterkit_max_mach_number)
    {
      // Ties go to the lowest index, so the answer does not depend on the thread count.
      if (local_squared > best_squared ||
          (local_squared == best_squared && local_squared > 0.0 && local_particle < best.particle)) {
        best_squared = local_squared;
        best.particle = local_particle;
      }
    }
  }
  best.value = std::sqrt(best_squared);
  return best;
}

void record_late_stage(RunAttributes& attributes, const LateStageRecord& record) {
  attributes.numbers["late_stage_transition_time"] = record.transition_time;
  attributes.numbers["late_stage_A_low"] = record.A_low;
  attributes.numbers["late_stage_max_mach_at_transition"] = record.max_mach_at_transition;
  attributes.texts["late_stage"] =
      "matrix equations of state replaced by P_m = A_low (rho_m/rho_m0 - 1); shear moduli scaled by A_low/A "
      "(physics.md section 3)";
}

}  // namespace craterkit::sph
