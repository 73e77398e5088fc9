#include "craterkit/study/axes.hpp"

#include <cmath>
#include <limits>

#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"

namespace craterkit::study {

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();
}  // namespace

const std::vector<NamedAxis>& named_axes() {
  static const std::vector<NamedAxis> axes = {
      {AxisKind::projectile_mass, "projectile_mass", 0.0, inf, true, true, "> 0 (kg)"},
      {AxisKind::projectile_radius, "projectile_radius", 0.0, inf, true, true, "> 0 (m)"},
      {AxisKind::impact_speed, "impact_speed", 0.0, inf, true, true, "> 0 (m/s)"},
      {AxisKind::cohesion, "cohesion", 0.0, inf, false, true, ">= 0 (Pa, the target's Lundborg cohesion)"},
      {AxisKind::friction, "friction", 0.0, inf, false, true, ">= 0 (the friction coefficient f)"},
      {AxisKind::angle_of_repose, "angle_of_repose", 0.0, 90.0, true, true, "in (0, 90) (degrees)"},
      {AxisKind::porosity, "porosity", 0.0, 1.0, true, true,
       "in (0, 1) (the fraction phi; initial distention 1 / (1 - phi))"},
      {AxisKind::A_low, "A_low", 0.0, inf, true, true, "> 0 (Pa)"},
      {AxisKind::t_transition, "t_transition", 0.0, inf, false, true, ">= 0 (s; 0: the rule 10 R_dom / c)"},
      {AxisKind::resolution, "resolution", 0.0, inf, true, true,
       "> 0 (spacings dx_max across the predicted crater radius)"},
  };
  return axes;
}

std::optional<NamedAxis> named_axis(std::string_view key) {
  for (const auto& axis : named_axes()) {
    if (axis.key == key) return axis;
  }
  return std::nullopt;
}

AxisKind axis_kind(std::string_view key, const std::string& where) {
  if (const auto axis = named_axis(key)) return axis->kind;
  if (key.starts_with("target.") && key.size() > 7) return AxisKind::material_key;
  if (key.find('.') != std::string_view::npos && key.front() != '.' && key.back() != '.') {
    return AxisKind::config_key;
  }
  std::string allowed;
  for (const auto& axis : named_axes())
    allowed += std::string(allowed.empty() ? "" : ", ") + std::string(axis.key);
  throw InputError(where + ": unknown axis '" + std::string(key) + "'; allowed: " + allowed +
                   ", a dotted configuration key (\"impact.grading\") or a target material key "
                   "(\"target.strength.limiting_strength\")");
}

bool changes_material(AxisKind kind) {
  return kind == AxisKind::cohesion || kind == AxisKind::friction || kind == AxisKind::angle_of_repose ||
         kind == AxisKind::porosity || kind == AxisKind::material_key;
}

void check_axis_value(const NamedAxis& axis, double value, const std::string& where) {
  const bool above = axis.lo_open ? value > axis.lo : value >= axis.lo;
  const bool below = axis.hi_open ? value < axis.hi : value <= axis.hi;
  if (!std::isfinite(value) || !above || !below) {
    throw InputError(where + ": value " + format_number(value) +
                     " not allowed: " + std::string(axis.allowed));
  }
}

std::optional<std::string> reserved_config_key(std::string_view dotted, bool sizing_enabled) {
  struct Reserved {
    std::string_view key;
    std::string_view instead;
    bool sizing_only;
  };
  static const Reserved reserved[] = {
      {"problem.name", "the run's name is set by the study", false},
      {"problem.setup", "a study runs impacts only", false},
      {"impact.projectile_mass", "use the axis projectile_mass (or projectile_radius)", false},
      {"impact.impact_speed", "use the axis impact_speed", false},
      {"impact.A_low", "use the axis A_low", false},
      {"impact.t_transition", "use the axis t_transition", false},
      {"target.strength.cohesion", "use the axis cohesion", false},
      {"target.strength.friction_coefficient", "use the axis friction (or angle_of_repose)", false},
      {"target.strength.repose_angle_degrees", "use the axis angle_of_repose", false},
      {"target.porosity.initial_distention", "use the axis porosity", false},
      {"impact.domain_radius", "set by the sizing rule; set [sizing] enabled = false to give it", true},
      {"impact.particle_spacing", "set by the sizing rule (the axis resolution changes it)", true},
      {"impact.inner_spacing", "set by the sizing rule ([sizing] core_spacing_over_projectile_radius)", true},
      {"run.end_time", "set by the sizing rule ([sizing] end_time_over_growth_time)", true},
  };
  for (const auto& r : reserved) {
    if (r.key == dotted && (sizing_enabled || !r.sizing_only)) return std::string(r.instead);
  }
  return std::nullopt;
}

}  // namespace craterkit::study
