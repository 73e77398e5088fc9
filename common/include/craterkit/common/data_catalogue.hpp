#pragma once
// Shipped data sets (materials, scaling constants, bodies, populations) are TOML files under
// data/<folder>/, addressed on the command line and in configurations either by name ("basalt") or by
// the path of any file with the same schema ("my/basalt.toml"). One resolver for all of them, so that
// every loader reports a missing name the same way; the files are read with TomlTable (toml_table.hpp).
#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include "craterkit/common/data_path.hpp"
#include "craterkit/common/input_error.hpp"

namespace craterkit {

// Sorted stems of data/<folder>/*.toml (empty if the folder does not exist).
inline std::vector<std::string> data_set_names(const std::string& folder) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(data_file(folder), ec)) {
    if (entry.is_regular_file() && entry.path().extension() == ".toml")
      names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// A name or a path: anything with a '/' or ending in ".toml" is a path; anything else a shipped name.
// Throws InputError naming `what` (e.g. "material", "body"), the value and the available names.
inline std::filesystem::path resolve_data_set(const std::string& name_or_path, const std::string& folder,
                                              const std::string& what) {
  const bool is_path = name_or_path.find('/') != std::string::npos || name_or_path.ends_with(".toml");
  const std::filesystem::path file =
      is_path ? std::filesystem::path(name_or_path) : data_file(folder) / (name_or_path + ".toml");
  if (!name_or_path.empty() && std::filesystem::is_regular_file(file)) return file;
  if (is_path) throw InputError(what + " file '" + name_or_path + "' does not exist");
  std::string names;
  for (const auto& n : data_set_names(folder)) names += (names.empty() ? "" : ", ") + n;
  throw InputError(what + " '" + name_or_path + "' is not known; available: " + names +
                   " (or give the path of a " + folder + " .toml file)");
}

}  // namespace craterkit
