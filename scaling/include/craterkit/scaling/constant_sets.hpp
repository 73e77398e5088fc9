#pragma once
// Published constant sets shipped in data/scaling/*.toml, loadable by name.
// Each file holds one set: its form, constants, a default strength where the source gives one,
// the target it describes, the citation, and its conventions (radius vs volume, pi2 factor, ...).
//
// File schema (unknown keys are errors naming the key):
//   name = "<file stem>"            description = "..."     citation = "..."
//   form = "holsapple" | "hh2011"   conventions = "..."     note = "..." (optional: transcription, doubts)
//   not_given = ["H2"]              (optional: coefficients the source does not give; they load as NaN
//                                    and are only an error when an impact needs them)
//   [constants]  K1, K2 (holsapple) or H1, H2 (hh2011), mu, nu
//   [target]     strength (Pa), density (kg/m^3)      (optional)
//   [published]  any keys: values as printed in the source when the constants were derived from them
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "craterkit/scaling/point_source.hpp"

namespace craterkit::scaling {

struct ConstantSet {
  std::string name;         // file stem, e.g. "jutzi2022_ryugu"
  std::string description;  // target material in words
  std::string citation;
  std::string conventions;  // what the constants mean (form, radius definition, ...)
  ScalingLaw law;
  std::optional<double> strength;        // Y, Pa, where the source gives one
  std::optional<double> target_density;  // rho, kg/m^3, where the source gives one
  std::string note;                      // transcription notes and doubts (may be empty)
  std::vector<std::string> not_given;    // coefficient names the source does not give (value NaN in law)
};

// Names of all shipped sets (sorted).
std::vector<std::string> constant_set_names();

// Loads data/scaling/<name>.toml; throws InputError listing the available names if unknown.
ConstantSet load_constant_set(const std::string& name);

// Loads any constant-set TOML file (same schema); errors name the key.
ConstantSet load_constant_set_file(const std::filesystem::path& path);

}  // namespace craterkit::scaling
