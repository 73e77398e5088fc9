// Loader of the published constant sets in data/scaling/*.toml (schema in constant_sets.hpp).
#include "craterkit/scaling/constant_sets.hpp"

#include <algorithm>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "craterkit/common/checks.hpp"
#include "craterkit/common/data_catalogue.hpp"
#include "craterkit/common/data_path.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/common/toml_table.hpp"

namespace craterkit::scaling {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

std::filesystem::path scaling_directory() {
  return data_file("scaling");
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

// not_given: the coefficients (of this form) the source does not give.
std::vector<std::string> read_not_given(TomlTable& root, Form form) {
  const std::vector<std::string> coefficients{coefficient_name(form, 1), coefficient_name(form, 2)};
  const auto names = root.texts("not_given").value_or(std::vector<std::string>{});
  for (const auto& name : names) {
    if (std::find(coefficients.begin(), coefficients.end(), name) == coefficients.end()) {
      root.fail("not_given", "value \"" + name + "\" not allowed: one of \"" + coefficients[0] + "\", \"" +
                                 coefficients[1] + "\" (the coefficients of form " + to_string(form) + ")");
    }
  }
  return names;
}

// A coefficient of [constants]: > 0, or NaN when the set lists it in not_given (and then absent).
double read_coefficient(TomlTable& constants, const std::string& name,
                        const std::vector<std::string>& not_given) {
  if (std::find(not_given.begin(), not_given.end(), name) != not_given.end()) {
    if (constants.contains(name)) constants.fail(name, "listed in not_given but also set");
    return std::numeric_limits<double>::quiet_NaN();
  }
  if (!constants.contains(name)) {
    constants.fail(name, "missing: a number in " + range_text(0.0, inf, true) +
                             " (list it in not_given if the source does not give it)");
  }
  return constants.required_number(name, 0.0, inf, true);
}

// [constants]: the two coefficients of the form, mu and nu; unknown keys are reported before missing ones.
ScalingLaw read_constants(TomlTable constants, Form form, const std::vector<std::string>& not_given) {
  ScalingLaw law;
  law.form = form;
  constants.reject_unknown({coefficient_name(form, 1), coefficient_name(form, 2), "mu", "nu"});
  law.coefficient_1 = read_coefficient(constants, coefficient_name(form, 1), not_given);
  law.coefficient_2 = read_coefficient(constants, coefficient_name(form, 2), not_given);
  law.mu = constants.required_number("mu", 0.0, 1.0, true);
  law.nu = constants.required_number("nu", 0.0, inf);
  constants.finish();
  return law;
}

// [target] (optional): the strength and density the source gives.
void read_target(TomlTable target, ConstantSet& set) {
  set.strength = target.optional_number("strength", 0.0, inf);
  set.target_density = target.optional_number("density", 0.0, inf, true);
  target.finish();
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
  const auto path = scaling_directory() / (name + ".toml");
  ConstantSet set = load_constant_set_file(path);
  if (set.name != name) {
    throw InputError(path.string() + ": name: value \"" + set.name +
                     "\" not allowed: must equal the file name \"" + name + "\"");
  }
  return set;
}

ConstantSet load_constant_set_file(const std::filesystem::path& path) {
  TomlTable root = TomlTable::parse_file(path);
  root.reject_unknown({"name", "description", "citation", "form", "conventions", "note", "not_given",
                       "constants", "target", "published"});
  ConstantSet set;
  set.name = root.required_text("name", "the file stem");
  set.description = root.required_text("description", "the target material in words");
  set.citation = root.required_text("citation", "the source of the constants");
  set.conventions = root.required_text("conventions", "what the constants mean");
  set.note = root.text("note", "");
  const Form form =
      form_from_string(root.required_text("form", "the form of the law", {"holsapple", "hh2011"}));
  set.not_given = read_not_given(root, form);
  set.law = read_constants(root.required_table("constants"), form, set.not_given);
  read_target(root.table("target"), set);
  (void)root.table("published");  // values as printed in the source: any keys, not read here
  root.finish();
  return set;
}

}  // namespace craterkit::scaling
