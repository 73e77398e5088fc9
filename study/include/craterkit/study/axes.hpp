#pragma once
// The axes of a study (docs/sweep.md, "Axes"): named axes with their units and ranges, dotted configuration
// keys ("impact.grading") and target-material keys ("target.strength.limiting_strength").
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace craterkit::study {

enum class AxisKind {
  projectile_mass,    // kg -> impact.projectile_mass
  projectile_radius,  // m -> impact.projectile_mass = 4/3 pi a^3 impact.projectile_density
  impact_speed,       // m/s -> impact.impact_speed
  cohesion,           // Pa -> the target material's strength.cohesion (Lundborg)
  friction,           // coefficient f -> strength.friction_coefficient
  angle_of_repose,    // degrees -> strength.friction_coefficient = friction_from_repose_angle(theta)
  porosity,           // phi -> porosity.initial_distention = 1 / (1 - phi)
  A_low,              // Pa -> impact.A_low
  t_transition,       // s -> impact.t_transition
  resolution,         // spacings across the predicted crater radius (the sizing rule's n)
  config_key,         // a dotted key of the run's configuration
  material_key,       // "target.<key>": a dotted key of the run's target material file
};

// A named axis: its key in a study file, its range (lo < v or lo <= v, v < hi or v <= hi) and unit.
struct NamedAxis {
  AxisKind kind;
  std::string_view key;
  double lo, hi;
  bool lo_open, hi_open;
  std::string_view allowed;  // the range and unit in words, for messages
};

const std::vector<NamedAxis>& named_axes();
// The named axis of a key, or nullopt for a dotted or unknown key.
std::optional<NamedAxis> named_axis(std::string_view key);
// The kind of any key; InputError for a key that is neither a named axis nor dotted (the message lists the
// allowed keys). `where` names the key in the message ("study.toml: grid.cohesoin").
AxisKind axis_kind(std::string_view key, const std::string& where);
// Whether a named axis changes the target material (cohesion, friction, angle_of_repose, porosity).
bool changes_material(AxisKind kind);

// Checks a named axis value against its range; InputError "<where>: value <v> not allowed: <allowed>".
void check_axis_value(const NamedAxis& axis, double value, const std::string& where);

// The configuration keys that a named axis or the sizing rule sets, so a dotted axis must not: the message
// says which axis to use instead. nullopt when the dotted key is free.
std::optional<std::string> reserved_config_key(std::string_view dotted, bool sizing_enabled);

}  // namespace craterkit::study
