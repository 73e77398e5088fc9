#include "craterkit/study/material_axes.hpp"

#include <numbers>

#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/sph/physics/yield_strength.hpp"

namespace craterkit::study {

double friction_from_angle_of_repose(double degrees) {
  return sph::friction_from_repose_angle(degrees * std::numbers::pi / 180.0);
}

double distention_from_porosity(double porosity) {
  return 1.0 / (1.0 - porosity);
}

namespace {

void require_lundborg(const TomlDocument& material, const std::string& where) {
  const auto model = material.text("strength.model");
  if (!model || *model != "lundborg") {
    throw InputError(where + ": the target material " + material.source() +
                     " has no Lundborg [strength] table (model = \"lundborg\"), so it has no cohesion or "
                     "friction to vary");
  }
}

}  // namespace

bool apply_material_axes(TomlDocument& material, const std::vector<AxisValue>& values,
                         const std::string& origin) {
  bool changed = false;
  for (const auto& v : values) {
    const std::string where = origin + "." + v.key;
    switch (v.kind) {
      case AxisKind::cohesion:
        require_lundborg(material, where);
        material.set_number("strength.cohesion", *v.number);
        changed = true;
        break;
      case AxisKind::friction:
      case AxisKind::angle_of_repose: {
        require_lundborg(material, where);
        const double f = v.kind == AxisKind::friction ? *v.number : friction_from_angle_of_repose(*v.number);
        material.erase("strength.repose_angle_degrees");
        material.set_number("strength.friction_coefficient", f);
        changed = true;
        break;
      }
      case AxisKind::porosity: {
        const auto model = material.text("porosity.model");
        if (!model || *model != "p_alpha") {
          throw InputError(where + ": the target material " + material.source() +
                           " has no P-alpha [porosity] table (model = \"p_alpha\"), so it has no porosity to "
                           "vary");
        }
        const double alpha0 = distention_from_porosity(*v.number);
        const double alpha_t = material.number("porosity.transition_distention").value_or(1.0);
        if (!(alpha0 > alpha_t)) {
          throw InputError(where + ": value " + format_number(*v.number) +
                           " not allowed: it gives alpha0 = " + format_number(alpha0) +
                           ", not above the material's porosity.transition_distention " +
                           format_number(alpha_t) + " (the crush curve needs alpha0 > alpha_t): allowed (" +
                           format_number(1.0 - 1.0 / alpha_t) + ", 1)");
        }
        material.set_number("porosity.initial_distention", alpha0);
        changed = true;
        break;
      }
      case AxisKind::material_key:
        try {
          material.set(v.key.substr(std::string("target.").size()), v.literal);
        } catch (const InputError& e) {
          throw InputError(where + ": " + e.what());
        }
        changed = true;
        break;
      default:
        break;
    }
  }
  return changed;
}

}  // namespace craterkit::study
