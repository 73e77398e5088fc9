#pragma once
// Shared by the libFuzzer targets: the input as a file (for readers that take a path), and the rule that
// bad input may only ever be a craterkit::InputError (any other exception, crash or sanitizer report is a
// finding).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace craterkit::fuzz {

// Writes the input to a per-process scratch file with the given extension and returns its path.
inline std::filesystem::path input_file(const std::uint8_t* data, std::size_t size,
                                        const std::string& extension) {
  const auto path =
      std::filesystem::temp_directory_path() / ("craterkit_fuzz_" + std::to_string(::getpid()) + extension);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

inline std::string input_text(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

}  // namespace craterkit::fuzz
