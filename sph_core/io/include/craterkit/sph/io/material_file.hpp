#pragma once
// Material files: data/materials/<name>.toml (schema in docs/materials.md) read into a Material.
#include <filesystem>
#include <string>
#include <vector>

#include "craterkit/sph/physics/material.hpp"

namespace craterkit::sph {

// name_or_path: a shipped material name ("basalt" -> <data>/materials/basalt.toml), or the path of any
// material TOML file (anything containing a '/' or ending in ".toml"). Throws craterkit::InputError for
// an unknown name (listing the shipped ones), a missing or unparsable file, an unknown key, a missing
// key, or an out-of-range value, naming the file and the key. The Material records the file and its hash
// (Material::source_file, source_hash).
Material load_material(const std::string& name_or_path);

// 16 hex digits of a 64-bit hash (FNV-1a) of the file's bytes; InputError naming the file if it cannot be
// read.
std::string file_hash(const std::filesystem::path& file);

// Names of the shipped materials (stems of <data>/materials/*.toml), sorted.
std::vector<std::string> material_names();

}  // namespace craterkit::sph
