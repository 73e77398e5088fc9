#include "craterkit/chronology/body.hpp"

#include <toml++/toml.h>
#include <algorithm>
#include <sstream>

#include "craterkit/common/data_catalogue.hpp"
#include "craterkit/common/data_path.hpp"
#include "craterkit/common/input_error.hpp"

namespace craterkit::chronology {
namespace {

void check_keys(const toml::table& t, const std::vector<std::string>& allowed, const std::string& where) {
  for (const auto& [key, node] : t) {
    const std::string k(key.str());
    if (std::find(allowed.begin(), allowed.end(), k) == allowed.end()) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      throw InputError(where + ": unknown key '" + k + "'; allowed: " + list);
    }
  }
}

double positive(const toml::table& t, const std::string& key, const std::string& where) {
  const auto* node = t.get(key);
  if (node == nullptr) throw InputError(where + ": missing key '" + key + "'");
  const auto v = node->value<double>();
  if (!v) throw InputError(where + ": key '" + key + "' must be a number");
  if (!(*v > 0.0)) {
    std::ostringstream os;
    os << where << ": " << key << " = " << *v << " must be > 0";
    throw InputError(os.str());
  }
  return *v;
}

std::optional<CollisionEnvironment> read_environment(const toml::table& t, const std::string& key,
                                                     const std::string& file) {
  const auto* sub = t.get_as<toml::table>(key);
  if (sub == nullptr) return std::nullopt;
  const std::string where = file + ": [" + key + "]";
  check_keys(*sub, {"intrinsic_collision_probability_km2_yr", "impact_speed_m_s", "citation"}, where);
  CollisionEnvironment env;
  env.intrinsic_probability_km2_yr = positive(*sub, "intrinsic_collision_probability_km2_yr", where);
  env.impact_speed = positive(*sub, "impact_speed_m_s", where);
  env.citation = (*sub)["citation"].value_or(std::string{});
  return env;
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
  return load_body_file(resolve_data_set(name_or_path, "bodies", "--body"));
}

Body load_body_file(const std::filesystem::path& path) {
  const std::string file = path.string();
  const toml::table t = parse_toml_file(path);
  check_keys(t,
             {"name", "mean_radius_m", "bulk_density_kg_m3", "surface_gravity_m_s2", "surface_area_m2",
              "main_belt", "near_earth", "citations"},
             file);
  Body b;
  b.name = t["name"].value_or(path.stem().string());
  b.mean_radius = positive(t, "mean_radius_m", file);
  b.bulk_density = positive(t, "bulk_density_kg_m3", file);
  b.surface_gravity = positive(t, "surface_gravity_m_s2", file);
  b.surface_area = positive(t, "surface_area_m2", file);
  b.main_belt = read_environment(t, "main_belt", file);
  b.near_earth = read_environment(t, "near_earth", file);
  if (const auto* c = t.get_as<toml::table>("citations")) {
    for (const auto& [key, node] : *c) {
      const auto s = node.value<std::string>();
      if (!s) throw InputError(file + ": [citations] " + std::string(key.str()) + " must be a string");
      b.citations += std::string(key.str()) + ": " + *s + "\n";
    }
  }
  return b;
}

}  // namespace craterkit::chronology
