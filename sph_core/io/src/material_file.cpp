#include "craterkit/sph/io/material_file.hpp"

#include <toml++/toml.h>
#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <optional>
#include <set>
#include <sstream>
#include <string_view>

#include "craterkit/common/data_catalogue.hpp"
#include "craterkit/common/data_path.hpp"
#include "craterkit/common/input_error.hpp"

namespace craterkit::sph {
namespace {

// Reads one table, remembering which keys were used so that the rest can be reported as unknown.
class TableReader {
 public:
  TableReader(const toml::table& table, std::string file, std::string prefix)
      : table_(table), file_(std::move(file)), prefix_(std::move(prefix)) {}

  [[nodiscard]] std::string key_name(std::string_view key) const { return prefix_ + std::string(key); }

  [[noreturn]] void fail(std::string_view key, const std::string& message) const {
    throw InputError(file_ + ": key '" + key_name(key) + "' " + message);
  }

  const toml::node* node(std::string_view key) {
    used_.insert(std::string(key));
    return table_.get(key);
  }

  std::optional<std::string> optional_string(std::string_view key) {
    const toml::node* n = node(key);
    if (n == nullptr) return std::nullopt;
    if (!n->is_string()) fail(key, "must be a string");
    return n->value<std::string>();
  }

  std::string required_string(std::string_view key) {
    auto s = optional_string(key);
    if (!s) fail(key, "is missing");
    return *s;
  }

  // A number (integer or floating point) that satisfies `allowed` (described in words for the error).
  std::optional<double> optional_number(std::string_view key, const std::function<bool(double)>& allowed,
                                        std::string_view allowed_text) {
    const toml::node* n = node(key);
    if (n == nullptr) return std::nullopt;
    if (!n->is_number()) fail(key, "must be a number");
    const double v = *n->value<double>();
    if (!std::isfinite(v) || !allowed(v)) {
      std::ostringstream text;
      text.precision(17);
      text << "= " << v << " is out of range: must be " << allowed_text;
      fail(key, text.str());
    }
    return v;
  }

  double required_number(std::string_view key, const std::function<bool(double)>& allowed,
                         std::string_view allowed_text) {
    auto v = optional_number(key, allowed, allowed_text);
    if (!v) fail(key, "is missing");
    return *v;
  }

  const toml::table* optional_table(std::string_view key) {
    const toml::node* n = node(key);
    if (n == nullptr) return nullptr;
    if (!n->is_table()) fail(key, "must be a table [" + key_name(key) + "]");
    return n->as_table();
  }

  const toml::table& required_table(std::string_view key) {
    const toml::node* n = node(key);
    if (n == nullptr) fail(key, "is missing (a table [" + key_name(key) + "])");
    if (!n->is_table()) fail(key, "must be a table [" + key_name(key) + "]");
    return *n->as_table();
  }

  void reject_unknown_keys(std::string_view allowed_text) const {
    for (const auto& [key, value] : table_) {
      if (!used_.contains(std::string(key.str()))) {
        throw InputError(file_ + ": unknown key '" + key_name(key.str()) +
                         "' (allowed: " + std::string(allowed_text) + ")");
      }
    }
  }

 private:
  const toml::table& table_;
  std::string file_;
  std::string prefix_;
  std::set<std::string> used_;
};

const auto positive = [](double v) { return v > 0.0; };
const auto non_negative = [](double v) { return v >= 0.0; };
const auto any_finite = [](double) { return true; };

Tillotson read_tillotson(TableReader& eos) {
  Tillotson m{};
  m.reference_density = eos.required_number("reference_density", positive, "> 0 (kg/m^3)");
  m.A = eos.required_number("A", positive, "> 0 (Pa)");
  m.B = eos.required_number("B", any_finite, "finite (Pa)");
  m.E0 = eos.required_number("E0", positive, "> 0 (J/kg)");
  m.E_iv = eos.required_number("E_iv", non_negative, ">= 0 (J/kg)");
  m.E_cv = eos.required_number(
      "E_cv", [&](double v) { return v > m.E_iv; }, "> E_iv (J/kg)");
  m.a = eos.required_number("a", non_negative, ">= 0");
  m.b = eos.required_number("b", non_negative, ">= 0");
  m.alpha = eos.required_number("alpha", non_negative, ">= 0");
  m.beta = eos.required_number("beta", non_negative, ">= 0");
  m.min_sound_speed_fraction =
      eos.optional_number(
             "min_sound_speed_fraction", [](double v) { return v > 0.0 && v <= 1.0; }, "in (0, 1]")
          .value_or(Tillotson{}.min_sound_speed_fraction);
  eos.reject_unknown_keys(
      "model, reference_density, A, B, E0, E_iv, E_cv, a, b, alpha, beta, min_sound_speed_fraction");
  return m;
}

LowSoundSpeed read_low_sound_speed(TableReader& eos) {
  LowSoundSpeed law{};
  law.reference_density = eos.required_number("reference_density", positive, "> 0 (kg/m^3)");
  law.A = eos.required_number("A", positive, "> 0 (Pa)");
  eos.reject_unknown_keys("model, reference_density, A");
  return law;
}

IdealGas read_ideal_gas(TableReader& eos) {
  IdealGas gas{eos.required_number(
      "gamma", [](double v) { return v > 1.0; }, "> 1")};
  eos.reject_unknown_keys("model, gamma");
  return gas;
}

// [strength]: model = "lundborg" (cohesion, friction_coefficient or repose_angle_degrees, limiting_strength)
// or "von_mises" (yield_strength).
StrengthModel read_strength(TableReader& strength) {
  const std::string model = strength.required_string("model");
  if (model == "lundborg") {
    LundborgStrength law{};
    law.cohesion = strength.required_number("cohesion", non_negative, ">= 0 (Pa)");
    const auto friction = strength.optional_number("friction_coefficient", non_negative, ">= 0");
    const auto repose = strength.optional_number(
        "repose_angle_degrees", [](double v) { return v > 0.0 && v < 90.0; }, "in (0, 90) degrees");
    if (friction && repose) {
      strength.fail("repose_angle_degrees",
                    "and 'strength.friction_coefficient' are both given: give exactly one (f = 2 sqrt(2) "
                    "sin(theta) / (3 - sin(theta)))");
    }
    if (!friction && !repose) {
      strength.fail("friction_coefficient", "is missing (give friction_coefficient or repose_angle_degrees)");
    }
    law.friction_coefficient =
        friction ? *friction : friction_from_repose_angle(*repose * std::numbers::pi / 180.0);
    law.limiting_strength =
        strength
            .optional_number(
                "limiting_strength", [&](double v) { return v > law.cohesion; }, "> cohesion (Pa)")
            .value_or(LundborgStrength{}.limiting_strength);
    if (!(law.limiting_strength > law.cohesion)) {  // the default 3.5 GPa against a larger cohesion
      strength.fail("cohesion", "must be below limiting_strength (Pa)");
    }
    strength.reject_unknown_keys(
        "model, cohesion, friction_coefficient, repose_angle_degrees, limiting_strength");
    return law;
  }
  if (model == "von_mises") {
    VonMisesStrength law{strength.required_number("yield_strength", positive, "> 0 (Pa)")};
    strength.reject_unknown_keys("model, yield_strength");
    return law;
  }
  strength.fail("model", "= \"" + model + "\" is not a known strength model (allowed: lundborg, von_mises)");
}

// [porosity]: model = "p_alpha" with the crush curve of physics.md section 2 and the porous sound speed.
PAlphaPorosity read_porosity(TableReader& porosity, const SolidReference& matrix) {
  const std::string model = porosity.required_string("model");
  if (model != "p_alpha") {
    porosity.fail("model", "= \"" + model + "\" is not a known porosity model (allowed: p_alpha)");
  }
  PAlphaPorosity out{};
  PAlphaParameters& p = out.crush_curve;
  p.transition_distention = porosity.required_number(
      "transition_distention", [](double v) { return v >= 1.0; }, ">= 1 (alpha_t)");
  p.initial_distention = porosity.required_number(
      "initial_distention", [&](double v) { return v >= p.transition_distention; },
      ">= transition_distention (alpha0 >= alpha_t >= 1)");
  p.elastic_pressure = porosity.required_number("elastic_pressure", non_negative, ">= 0 (P_e, Pa)");
  p.transition_pressure = porosity.required_number(
      "transition_pressure", [&](double v) { return v > p.elastic_pressure; }, "> elastic_pressure (Pa)");
  p.solid_pressure = porosity.required_number(
      "solid_pressure", [&](double v) { return v > p.transition_pressure; }, "> transition_pressure (Pa)");
  p.exponent_1 = porosity.required_number("exponent_1", positive, "> 0 (n1)");
  p.exponent_2 = porosity.required_number("exponent_2", positive, "> 0 (n2)");
  out.matrix_sound_speed = std::sqrt(matrix.bulk_modulus / matrix.density);
  std::ostringstream bound;
  bound.precision(6);
  bound << "> 0 and <= the matrix sound speed sqrt(eos.A / eos.reference_density) = "
        << out.matrix_sound_speed << " (m/s)";
  out.porous_sound_speed = porosity.required_number(
      "porous_sound_speed", [&](double v) { return v > 0.0 && v <= out.matrix_sound_speed; }, bound.str());
  porosity.reject_unknown_keys(
      "model, initial_distention, transition_distention, elastic_pressure, transition_pressure, "
      "solid_pressure, exponent_1, exponent_2, porous_sound_speed");
  return out;
}

Material parse_material(const toml::table& root, const std::string& name, const std::string& file) {
  TableReader top(root, file, "");
  Material material{};
  material.name = name;
  material.citation = top.required_string("citation");
  material.description = top.optional_string("description").value_or("");

  TableReader eos(top.required_table("eos"), file, "eos.");
  const std::string model = eos.required_string("model");
  if (model == "tillotson" || model == "low_sound_speed") {
    if (model == "tillotson") {
      material.eos = read_tillotson(eos);
    } else {
      material.eos = read_low_sound_speed(eos);
    }
    material.shear_modulus = top.required_number("shear_modulus", non_negative, ">= 0 (Pa)");
  } else if (model == "ideal_gas") {
    material.eos = read_ideal_gas(eos);
    material.shear_modulus = top.optional_number(
                                    "shear_modulus", [](double v) { return v == 0.0; }, "0 for an ideal gas")
                                 .value_or(0.0);
  } else {
    eos.fail("model",
             "= \"" + model +
                 "\" is not a known equation of state (allowed: tillotson, low_sound_speed, ideal_gas)");
  }

  const auto solid = solid_reference(material.eos);
  if (const toml::table* table = top.optional_table("strength")) {
    if (!solid) top.fail("strength", "is given for an ideal gas: strength needs a solid equation of state");
    if (!(material.shear_modulus > 0.0)) {
      top.fail("shear_modulus",
               "= 0 with a [strength] table: a material with strength needs shear_modulus > 0");
    }
    TableReader strength(*table, file, "strength.");
    material.strength = read_strength(strength);
  }
  if (const toml::table* table = top.optional_table("porosity")) {
    if (!solid)
      top.fail("porosity", "is given for an ideal gas: porosity needs a solid matrix equation of state");
    TableReader porosity(*table, file, "porosity.");
    material.porosity = read_porosity(porosity, *solid);
  }
  top.reject_unknown_keys("description, citation, shear_modulus, [eos], [strength], [porosity]");
  return material;
}

}  // namespace

std::vector<std::string> material_names() {
  return data_set_names("materials");
}

Material load_material(const std::string& name_or_path) {
  const auto file = resolve_data_set(name_or_path, "materials", "material");
  return parse_material(parse_toml_file(file), file.stem().string(), file.string());
}

}  // namespace craterkit::sph
