#include "craterkit/sph/io/material_file.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "craterkit/common/data_catalogue.hpp"
#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/common/toml_table.hpp"

namespace craterkit::sph {
namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// A number that must exceed (or, with or_equal, reach) another key's value: read as any finite number,
// then checked against the other key, so that the message names that key.
double read_above(TomlTable& t, std::string_view k, std::string_view other, double other_value,
                  bool or_equal = false) {
  const double v = t.required_number(k, -inf, inf);
  if (or_equal ? !(v >= other_value) : !(v > other_value)) {
    t.out_of_range(
        k, v, std::string(or_equal ? ">= " : "> ") + std::string(other) + " = " + format_number(other_value));
  }
  return v;
}

Tillotson read_tillotson(TomlTable& eos) {
  Tillotson m{};
  m.reference_density = eos.required_number("reference_density", 0.0, inf, true);
  m.A = eos.required_number("A", 0.0, inf, true);
  m.B = eos.required_number("B", -inf, inf);
  m.E0 = eos.required_number("E0", 0.0, inf, true);
  m.E_iv = eos.required_number("E_iv", 0.0, inf);
  m.E_cv = read_above(eos, "E_cv", "E_iv", m.E_iv);
  m.a = eos.required_number("a", 0.0, inf);
  m.b = eos.required_number("b", 0.0, inf);
  m.alpha = eos.required_number("alpha", 0.0, inf);
  m.beta = eos.required_number("beta", 0.0, inf);
  m.min_sound_speed_fraction =
      eos.number("min_sound_speed_fraction", Tillotson{}.min_sound_speed_fraction, 0.0, 1.0, true);
  eos.finish();
  return m;
}

LowSoundSpeed read_low_sound_speed(TomlTable& eos) {
  LowSoundSpeed law{};
  law.reference_density = eos.required_number("reference_density", 0.0, inf, true);
  law.A = eos.required_number("A", 0.0, inf, true);
  eos.finish();
  return law;
}

IdealGas read_ideal_gas(TomlTable& eos) {
  IdealGas gas{eos.required_number("gamma", 1.0, inf, true)};
  eos.finish();
  return gas;
}

// [strength] model = "lundborg": cohesion, friction_coefficient or repose_angle_degrees (exactly one),
// limiting_strength above the cohesion, weakening_strain ("total", the default; "plastic_after_switch";
// "plastic").
LundborgStrength read_lundborg(TomlTable& strength) {
  LundborgStrength law{};
  law.cohesion = strength.required_number("cohesion", 0.0, inf);
  const auto friction = strength.optional_number("friction_coefficient", 0.0, inf);
  const auto repose = strength.optional_number("repose_angle_degrees", 0.0, 90.0, true, true);
  if (friction && repose) {
    strength.fail("repose_angle_degrees", "and " + strength.key("friction_coefficient") +
                                              " are both given: give exactly one (f = 2 sqrt(2) sin(theta) / "
                                              "(3 - sin(theta)))");
  }
  if (!friction && !repose) {
    strength.fail("friction_coefficient", "missing: give friction_coefficient or repose_angle_degrees");
  }
  law.friction_coefficient =
      friction ? *friction : friction_from_repose_angle(*repose * std::numbers::pi / 180.0);
  if (strength.contains("limiting_strength")) {
    law.limiting_strength = read_above(strength, "limiting_strength", "cohesion", law.cohesion);
  } else {
    strength.accept("limiting_strength");
  }
  const std::string weakening =
      strength.text("weakening_strain", "total", {"total", "plastic_after_switch", "plastic"});
  if (weakening == "plastic_after_switch") law.weakening_strain = WeakeningStrain::plastic_after_switch;
  if (weakening == "plastic") law.weakening_strain = WeakeningStrain::plastic;
  if (!(law.limiting_strength > law.cohesion)) {  // the default 3.5 GPa against a larger cohesion
    strength.out_of_range("cohesion", law.cohesion,
                          "< limiting_strength = " + format_number(law.limiting_strength) + " (its default)");
  }
  strength.finish();
  return law;
}

// [strength]: model = "lundborg" or "von_mises" (yield_strength).
StrengthModel read_strength(TomlTable& strength) {
  const std::string model = strength.required_text(
      "model", "the strength model (\"lundborg\" or \"von_mises\")", {"lundborg", "von_mises"});
  if (model == "lundborg") return read_lundborg(strength);
  VonMisesStrength law{strength.required_number("yield_strength", 0.0, inf, true)};
  strength.finish();
  return law;
}

// [porosity]: model = "p_alpha" with the crush curve of docs/physics.md section 2 and the porous sound speed,
// which must not exceed the matrix sound speed.
PAlphaPorosity read_porosity(TomlTable& porosity, const SolidReference& matrix) {
  (void)porosity.required_text("model", "the porosity model (\"p_alpha\")", {"p_alpha"});
  PAlphaPorosity out{};
  PAlphaParameters& p = out.crush_curve;
  p.transition_distention = porosity.required_number("transition_distention", 1.0, inf);
  p.initial_distention =
      read_above(porosity, "initial_distention", "transition_distention", p.transition_distention, true);
  p.elastic_pressure = porosity.required_number("elastic_pressure", 0.0, inf);
  p.transition_pressure = read_above(porosity, "transition_pressure", "elastic_pressure", p.elastic_pressure);
  p.solid_pressure = read_above(porosity, "solid_pressure", "transition_pressure", p.transition_pressure);
  p.exponent_1 = porosity.required_number("exponent_1", 0.0, inf, true);
  p.exponent_2 = porosity.required_number("exponent_2", 0.0, inf, true);
  out.matrix_sound_speed = std::sqrt(matrix.bulk_modulus / matrix.density);
  out.porous_sound_speed = porosity.required_number("porous_sound_speed", -inf, inf);
  if (!(out.porous_sound_speed > 0.0 && out.porous_sound_speed <= out.matrix_sound_speed)) {
    porosity.out_of_range("porous_sound_speed", out.porous_sound_speed,
                          "(0, " + format_number(out.matrix_sound_speed) +
                              "], at most the matrix sound speed sqrt(eos.A / eos.reference_density) (m/s)");
  }
  porosity.finish();
  return out;
}

// [eos] and the shear modulus that goes with it: required for a solid, 0 (or absent) for an ideal gas.
void read_eos(TomlTable& top, Material& material) {
  TomlTable eos = top.required_table("eos");
  const std::string model =
      eos.required_text("model", "the equation of state", {"tillotson", "low_sound_speed", "ideal_gas"});
  if (model == "ideal_gas") {
    material.eos = read_ideal_gas(eos);
    material.shear_modulus = top.number("shear_modulus", 0.0, -inf, inf);
    if (material.shear_modulus != 0.0)
      top.out_of_range("shear_modulus", material.shear_modulus, "0 for an ideal gas");
    return;
  }
  if (model == "tillotson") {
    material.eos = read_tillotson(eos);
  } else {
    material.eos = read_low_sound_speed(eos);
  }
  material.shear_modulus = top.required_number("shear_modulus", 0.0, inf);
}

Material parse_material(TomlTable& top, const std::string& name) {
  Material material{};
  material.name = name;
  material.citation = top.required_text("citation", "the source of the values");
  material.description = top.text("description", "");
  read_eos(top, material);
  const auto solid = solid_reference(material.eos);
  TomlTable strength = top.table("strength");
  if (top.contains("strength")) {
    if (!solid) top.fail("strength", "given for an ideal gas: strength needs a solid equation of state");
    if (!(material.shear_modulus > 0.0)) {
      top.out_of_range("shear_modulus", material.shear_modulus,
                       "> 0 with a [strength] table (a material with strength needs a shear modulus)");
    }
    material.strength = read_strength(strength);
  }
  TomlTable porosity = top.table("porosity");
  if (top.contains("porosity")) {
    if (!solid)
      top.fail("porosity", "given for an ideal gas: porosity needs a solid matrix equation of state");
    material.porosity = read_porosity(porosity, *solid);
  }
  top.finish();
  return material;
}

}  // namespace

std::string file_hash(const std::filesystem::path& file) {
  // FNV-1a, 64 bits: enough to notice an edited file (not a defence against a deliberate collision).
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot open the file to hash it");
  std::uint64_t hash = 0xcbf29ce484222325ULL;
  std::vector<char> buffer(1 << 16);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    const auto n = static_cast<std::size_t>(in.gcount());
    for (std::size_t i = 0; i < n; ++i) {
      hash ^= static_cast<std::uint8_t>(buffer[i]);
      hash *= 0x100000001b3ULL;
    }
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(hash));
  return text;
}

std::vector<std::string> material_names() {
  return data_set_names("materials");
}

Material load_material(const std::string& name_or_path) {
  const auto file = resolve_data_set(name_or_path, "materials", "material");
  TomlTable top = TomlTable::parse_file(file);
  Material material = parse_material(top, file.stem().string());
  material.source_file = file.string();
  material.source_hash = file_hash(file);
  return material;
}

}  // namespace craterkit::sph
