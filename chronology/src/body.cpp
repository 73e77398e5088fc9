#include "craterkit/chronology/body.hpp"

#include <limits>

#include "craterkit/common/data_catalogue.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/common/toml_table.hpp"

namespace craterkit::chronology {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// [main_belt] or [near_earth] (optional): where the body spends its time among the projectiles.
std::optional<CollisionEnvironment> read_environment(TomlTable& body, const std::string& key) {
  TomlTable t = body.table(key);
  if (!body.contains(key)) return std::nullopt;
  t.reject_unknown({"intrinsic_collision_probability_km2_yr", "impact_speed_m_s", "citation"});
  CollisionEnvironment env;
  env.intrinsic_probability_km2_yr =
      t.required_number("intrinsic_collision_probability_km2_yr", 0.0, inf, true);
  env.impact_speed = t.required_number("impact_speed_m_s", 0.0, inf, true);
  env.citation = t.text("citation", "");
  t.finish();
  return env;
}

// [citations]: one string per value, any keys; kept as "key: text" lines.
std::string read_citations(TomlTable citations) {
  std::string out;
  for (const auto& key : citations.keys()) {
    out += key + ": " + citations.required_text(key, "a citation") + "\n";
  }
  return out;
}

}  // namespace

const CollisionEnvironment& environment(const Body& body, CollisionRegion region) {
  const auto& env = region == CollisionRegion::main_belt ? body.main_belt : body.near_earth;
  if (!env) {
    throw InputError("body '" + body.name + "' has no [" + to_string(region) +
                     "] collision environment; add one to its TOML file or choose the other region");
  }
  return *env;
}

std::vector<std::string> body_names() {
  return data_set_names("bodies");
}

Body load_body(const std::string& name_or_path) {
  return load_body_file(resolve_data_set(name_or_path, "bodies", "body"));
}

Body load_body_file(const std::filesystem::path& path) {
  TomlTable t = TomlTable::parse_file(path);
  t.reject_unknown({"name", "mean_radius_m", "bulk_density_kg_m3", "surface_gravity_m_s2", "surface_area_m2",
                    "main_belt", "near_earth", "citations"});
  Body b;
  b.name = t.text("name", path.stem().string());
  b.mean_radius = t.required_number("mean_radius_m", 0.0, inf, true);
  b.bulk_density = t.required_number("bulk_density_kg_m3", 0.0, inf, true);
  b.surface_gravity = t.required_number("surface_gravity_m_s2", 0.0, inf, true);
  b.surface_area = t.required_number("surface_area_m2", 0.0, inf, true);
  b.main_belt = read_environment(t, "main_belt");
  b.near_earth = read_environment(t, "near_earth");
  b.citations = read_citations(t.table("citations"));
  t.finish();
  return b;
}

}  // namespace craterkit::chronology
