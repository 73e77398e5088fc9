#pragma once
// Published constant sets shipped in data/scaling/*.toml, loadable by name.
// Each file holds one set: its form, constants, a default strength where the source gives one,
// the target it describes, the citation, and its conventions (radius vs volume, pi2 factor, ...).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "craterkit/scaling/point_source.hpp"

namespace craterkit::scaling {

struct ConstantSet {
  std::string name;            // file stem, e.g. "jutzi2022_ryugu"
  std::string description;     // target material in words
  std::string citation;
  std::string conventions;     // what the constants mean (form, radius definition, ...)
  ScalingLaw law;
  std::optional<double> strength;        // Y, Pa, where the source gives one
  std::optional<double> target_density;  // rho, kg/m^3, where the source gives one
};

// Names of all shipped sets (sorted).
std::vector<std::string> constant_set_names();

// Loads data/scaling/<name>.toml; throws InputError listing the available names if unknown.
ConstantSet load_constant_set(const std::string& name);

// Loads any constant-set TOML file (same schema); errors name the key.
ConstantSet load_constant_set_file(const std::filesystem::path& path);

}  // namespace craterkit::scaling
