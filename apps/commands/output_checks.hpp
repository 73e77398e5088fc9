#pragma once
// Checks of command-line flags shared by the subcommands: thread counts, and output paths, which are
// checked before any work so that a long computation never ends on an unwritable path.
#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "craterkit/common/input_error.hpp"

namespace craterkit::cli {

// The largest thread count a flag accepts: four times the processors this process may run on. More
// threads than that only oversubscribe the machine, and very large counts crash the OpenMP runtime.
inline int max_threads() {
  return std::max(4, 4 * omp_get_num_procs());
}

// A thread-count flag: 0 (the default: all processors) or 1 to max_threads().
inline void check_threads(const std::string& flag, long long threads) {
  if (threads < 0 || threads > max_threads()) {
    throw InputError(flag + " " + std::to_string(threads) + ": allowed 1 to " +
                     std::to_string(max_threads()) + " (four times the " +
                     std::to_string(omp_get_num_procs()) +
                     " processors available), or leave it out to use all processors");
  }
}

// The nearest existing folder at or above `path` (the folder a new path would be created in).
inline std::filesystem::path existing_ancestor(const std::filesystem::path& path) {
  std::filesystem::path p = std::filesystem::absolute(path);
  std::error_code ec;
  while (!p.empty() && !std::filesystem::exists(p, ec) && p != p.parent_path()) p = p.parent_path();
  return p;
}

// An output folder: a folder, or a path that can be created as one (its nearest existing ancestor is a
// writable folder).
inline void check_output_folder(const std::string& flag, const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_directory(path, ec))
    throw InputError(flag + " " + path.string() + ": exists and is not a folder");
  const auto base = existing_ancestor(path);
  if (!std::filesystem::is_directory(base, ec))
    throw InputError(flag + " " + path.string() + ": " + base.string() + " is not a folder");
  if (::access(base.c_str(), W_OK | X_OK) != 0)
    throw InputError(flag + " " + path.string() + ": folder " + base.string() + " is not writable");
}

// An output file: not a folder, in an existing writable folder.
inline void check_output_file(const std::string& flag, const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(flag + " " + path.string() + ": is a folder");
  const auto folder = std::filesystem::absolute(path).parent_path();
  if (!std::filesystem::is_directory(folder, ec))
    throw InputError(flag + " " + path.string() + ": folder " + folder.string() + " does not exist");
  if (::access(folder.c_str(), W_OK | X_OK) != 0)
    throw InputError(flag + " " + path.string() + ": folder " + folder.string() + " is not writable");
}

// The numbers of a comma-separated list option, given once or several times ("0,0.05,1"): an empty element
// ("0,,1", a comma at an end) or one that is not a number is an error naming the flag, never a 0 or a
// dropped value. Use with add_option_function<std::vector<std::string>>.
inline std::vector<double> number_list(const std::string& flag, const std::vector<std::string>& items) {
  std::vector<double> out;
  for (const auto& item : items) {
    for (std::size_t start = 0;;) {
      const auto comma = item.find(',', start);
      std::string text = item.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
      const auto first = text.find_first_not_of(" \t");
      text = first == std::string::npos ? std::string()
                                        : text.substr(first, text.find_last_not_of(" \t") - first + 1);
      if (text.empty()) {
        throw InputError(
            flag + " " + item +
            ": an empty element (two commas in a row, or a comma at an end); give a number between "
            "every two commas");
      }
      char* end = nullptr;
      const double value = std::strtod(text.c_str(), &end);
      if (end == text.c_str() || *end != '\0')
        throw InputError(flag + " " + item + ": '" + text + "' is not a number");
      out.push_back(value);
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
  }
  return out;
}

}  // namespace craterkit::cli
