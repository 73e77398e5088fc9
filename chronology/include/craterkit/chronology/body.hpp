#pragma once
// Target bodies (data/bodies/<name>.toml): the values that turn impactor numbers into crater
// densities. Every shipped value carries its citation in the file.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "craterkit/chronology/conventions.hpp"

namespace craterkit::chronology {

// Collision environment of one region: Bottke et al. (1994) intrinsic collision probability P_i
// (impacts per year per km^2 of (R_t + a)^2 per projectile) and the mean impact speed.
struct CollisionEnvironment {
  double intrinsic_probability_km2_yr = 0.0;  // P_i, km^-2 yr^-1
  double impact_speed = 0.0;                  // m/s
  std::string citation;
};

struct Body {
  std::string name;
  double mean_radius = 0.0;      // m
  double bulk_density = 0.0;     // kg/m^3
  double surface_gravity = 0.0;  // m/s^2
  double surface_area = 0.0;     // m^2
  std::optional<CollisionEnvironment> main_belt;
  std::optional<CollisionEnvironment> near_earth;
  std::string citations;  // one line per value, as stated in the file
};

// The environment for `region`; throws InputError if the body file gives none for it.
const CollisionEnvironment& environment(const Body& body, CollisionRegion region);

// Body TOML: name, mean_radius_m, bulk_density_kg_m3, surface_gravity_m_s2, surface_area_m2, and optional
// tables [main_belt] / [near_earth] with intrinsic_collision_probability_km2_yr, impact_speed_m_s, citation,
// plus a [citations] table of strings (one per value). Unknown keys and non-positive values are errors.
std::vector<std::string> body_names();
Body load_body(const std::string& name_or_path);  // "ryugu" | "bennu" | path to a .toml
Body load_body_file(const std::filesystem::path& path);

}  // namespace craterkit::chronology
