// Loader of the published constant sets in data/scaling/*.toml (schema in constant_sets.hpp).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "craterkit/common/data_catalogue.hpp"
#include "craterkit/common/data_path.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/constant_sets.hpp"

namespace craterkit::scaling {
namespace {

std::filesystem::path scaling_directory() {
  return data_file("scaling");
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

std::string required_string(const toml::table& table, const std::string& key, const std::string& where) {
  const auto* node = table.get(key);
  if (node == nullptr) throw InputError(where + ": key '" + key + "' is missing (a string is required)");
  const auto value = node->value<std::string>();
  if (!value || node->type() != toml::node_type::string || value->empty()) {
    throw InputError(where + ": key '" + key + "' must be a non-empty string");
  }
  return *value;
}

double number_at(const toml::node& node, const std::string& key, const std::string& where) {
  if (!node.is_number()) throw InputError(where + ": key '" + key + "' must be a number");
  const double value = *node.value<double>();
  if (!std::isfinite(value)) throw InputError(where + ": key '" + key + "' must be finite");
  return value;
}

void reject_unknown_keys(const toml::table& table, const std::set<std::string>& allowed,
                         const std::string& where) {
  for (const auto& [key, node] : table) {
    (void)node;
    if (!allowed.contains(std::string(key.str()))) {
      std::vector<std::string> names(allowed.begin(), allowed.end());
      throw InputError(where + ": unknown key '" + std::string(key.str()) + "'; allowed: " + join(names));
    }
  }
}

}  // namespace

std::vector<std::string> constant_set_names() {
  return data_set_names("scaling");
}

ConstantSet load_constant_set(const std::string& name) {
  const auto names = constant_set_names();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    throw InputError("scaling constant set '" + name + "' is not known; available: " + join(names));
  }
  ConstantSet set = load_constant_set_file(scaling_directory() / (name + ".toml"));
  if (set.name != name) {
    throw InputError((scaling_directory() / (name + ".toml")).string() + ": key 'name' is '" + set.name +
                     "' but must equal the file name '" + name + "'");
  }
  return set;
}

ConstantSet load_constant_set_file(const std::filesystem::path& path) {
  const std::string where = path.string();
  const toml::table root = parse_toml_file(path);
  reject_unknown_keys(root,
                      {"name", "description", "citation", "form", "conventions", "note", "not_given",
                       "constants", "target", "published"},
                      where);
  ConstantSet set;
  set.name = required_string(root, "name", where);
  set.description = required_string(root, "description", where);
  set.citation = required_string(root, "citation", where);
  set.conventions = required_string(root, "conventions", where);
  if (root.contains("note")) set.note = required_string(root, "note", where);
  const std::string form_text = required_string(root, "form", where);
  try {
    set.law.form = form_from_string(form_text);
  } catch (const InputError& error) {
    throw InputError(where + ": key 'form': " + error.what());
  }
  const bool holsapple = set.law.form == Form::holsapple;
  const std::string c1 = holsapple ? "K1" : "H1";
  const std::string c2 = holsapple ? "K2" : "H2";

  if (const auto* node = root.get("not_given")) {
    const auto* array = node->as_array();
    if (array == nullptr) throw InputError(where + ": key 'not_given' must be an array of constant names");
    for (const auto& item : *array) {
      const auto text = item.value<std::string>();
      if (!text || (*text != c1 && *text != c2)) {
        throw InputError(where + ": key 'not_given' may only list " + c1 + " or " + c2 + " (form " +
                         form_text + ")");
      }
      set.not_given.push_back(*text);
    }
  }

  const auto* constants = root.get_as<toml::table>("constants");
  if (constants == nullptr) throw InputError(where + ": table [constants] is missing");
  reject_unknown_keys(*constants, {c1, c2, "mu", "nu"}, where + " [constants]");
  const auto constant = [&](const std::string& key) -> double {
    const bool absent_by_design =
        std::find(set.not_given.begin(), set.not_given.end(), key) != set.not_given.end();
    const auto* node = constants->get(key);
    if (absent_by_design) {
      if (node != nullptr)
        throw InputError(where + ": [constants] " + key + " is listed in not_given but also set");
      return std::numeric_limits<double>::quiet_NaN();
    }
    if (node == nullptr) {
      throw InputError(where + ": [constants] key '" + key +
                       "' is missing (list it in not_given if the source " + "does not give it)");
    }
    const double value = number_at(*node, key, where + " [constants]");
    if (key == "nu" ? value < 0.0 : value <= 0.0) {
      throw InputError(where + ": [constants] " + key + " = " + std::to_string(value) + " is out of range (" +
                       (key == "nu" ? ">= 0" : "> 0") + ")");
    }
    return value;
  };
  set.law.coefficient_1 = constant(c1);
  set.law.coefficient_2 = constant(c2);
  set.law.mu = constant("mu");
  set.law.nu = constant("nu");
  if (set.law.mu > 1.0) throw InputError(where + ": [constants] mu must be <= 1 (1/3 .. 2/3 expected)");

  if (const auto* node = root.get("target")) {
    const auto* target = node->as_table();
    if (target == nullptr) throw InputError(where + ": key 'target' must be a table");
    reject_unknown_keys(*target, {"strength", "density"}, where + " [target]");
    if (const auto* strength = target->get("strength")) {
      set.strength = number_at(*strength, "strength", where + " [target]");
      if (*set.strength < 0.0) throw InputError(where + ": [target] strength must be >= 0 Pa");
    }
    if (const auto* density = target->get("density")) {
      set.target_density = number_at(*density, "density", where + " [target]");
      if (*set.target_density <= 0.0) throw InputError(where + ": [target] density must be > 0 kg/m^3");
    }
  }
  if (const auto* node = root.get("published"); node != nullptr && !node->is_table()) {
    throw InputError(where + ": key 'published' must be a table");
  }
  return set;
}

}  // namespace craterkit::scaling
