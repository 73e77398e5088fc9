#pragma once
// Locates the shipped data directory (materials, scaling constants, bodies, populations, examples).
// Order:
//  1. $CRATERKIT_DATA_DIR when set (it must be a directory);
//  2. relative to the binary that holds this code (the program, or a shared module such as the Python
//     extension): the first ancestor folder of the binary, up to five levels up, that has
//     <datadir>/craterkit/ (share/craterkit/ by default), so an installed tree works wherever it is moved
//     (a binary inside the build tree looks no higher than the build tree);
//  3. the source tree's data/, only for a binary that lies inside the build tree it was built in;
//  4. the install prefix configured at build time (for programs of other projects that link the static
//     libraries).
// The result is computed once per process.
#include <filesystem>
#include <string>

namespace craterkit {

// Throws std::runtime_error naming the places searched when none holds the data.
std::filesystem::path data_directory();

// data_file("scaling/jutzi2022_ryugu.toml") -> absolute path inside the data directory.
inline std::filesystem::path data_file(const std::filesystem::path& relative) {
  return data_directory() / relative;
}

// How the data directory was found: "CRATERKIT_DATA_DIR", "installation", "source tree" or
// "configured prefix" (for `craterkit list` and diagnostics).
std::string data_directory_origin();

}  // namespace craterkit
