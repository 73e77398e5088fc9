#pragma once
// Locates the shipped data directory (materials, scaling constants, bodies, populations, examples).
// Order: $CRATERKIT_DATA_DIR, the source tree of a build-tree binary, the installed share directory.
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace craterkit {

inline std::filesystem::path data_directory() {
  if (const char* env = std::getenv("CRATERKIT_DATA_DIR"); env != nullptr && *env != '\0') {
    return env;
  }
#ifdef CRATERKIT_SOURCE_DATA_DIR
  if (std::filesystem::is_directory(CRATERKIT_SOURCE_DATA_DIR)) return CRATERKIT_SOURCE_DATA_DIR;
#endif
  if (std::filesystem::is_directory(CRATERKIT_INSTALL_DATA_DIR)) return CRATERKIT_INSTALL_DATA_DIR;
  throw std::runtime_error(
      "craterkit data directory not found: set CRATERKIT_DATA_DIR to the 'data' folder of craterkit "
      "(looked in " CRATERKIT_INSTALL_DATA_DIR ")");
}

// data_file("scaling/jutzi2022_ryugu.toml") -> absolute path inside the data directory.
inline std::filesystem::path data_file(const std::filesystem::path& relative) {
  return data_directory() / relative;
}

}  // namespace craterkit
