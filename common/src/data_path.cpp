// Run-time lookup of the data directory (see data_path.hpp for the order).
#include "craterkit/common/data_path.hpp"

#include <dlfcn.h>

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <utility>
#include <vector>

namespace craterkit {
namespace {

namespace fs = std::filesystem;

// The files of the program and of the shared object that hold this function, most specific first.
std::vector<fs::path> binary_locations() {
  std::vector<fs::path> out;
  std::error_code ec;
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&binary_locations), &info) != 0 && info.dli_fname != nullptr &&
      *info.dli_fname != '\0') {
    // For the main program dladdr reports argv[0], which may be relative or a bare name; it is used
    // only when it names an existing file, and /proc/self/exe below covers the rest.
    const fs::path named(info.dli_fname);
    if (named.has_parent_path() && fs::is_regular_file(named, ec)) {
      const fs::path canonical = fs::canonical(named, ec);
      if (!ec) out.push_back(canonical);
    }
  }
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) out.push_back(self);
  return out;
}

bool holds_data(const fs::path& dir) {
  std::error_code ec;
  return fs::is_directory(dir / "scaling", ec) && fs::is_directory(dir / "bodies", ec);
}

// Whether `file` (an absolute, canonical path) is `dir` or lies below it.
bool inside(const fs::path& file, const fs::path& dir) {
  std::error_code ec;
  const fs::path root = fs::weakly_canonical(dir, ec);
  if (ec) return false;
  const auto [root_end, unused] = std::mismatch(root.begin(), root.end(), file.begin(), file.end());
  (void)unused;
  return root_end == root.end();
}

// The data directory without the environment variable.
std::pair<fs::path, std::string> locate() {
  const auto binaries = binary_locations();
  std::string searched;
  for (const auto& binary : binaries) {
    // A binary of the build tree looks no higher than the build tree itself (an installation into a folder
    // of it still counts), so that an unrelated installation above it is never taken for its data.
    const bool in_build_tree = inside(binary, CRATERKIT_BUILD_DIR);
    fs::path dir = binary.parent_path();
    for (int level = 0; level < 6 && !dir.empty(); ++level) {
      if (in_build_tree && !inside(dir, CRATERKIT_BUILD_DIR)) break;
      const fs::path candidate = dir / CRATERKIT_RELATIVE_DATA_DIR;
      if (holds_data(candidate)) return {candidate, "installation"};
      if (dir == dir.root_path()) break;
      dir = dir.parent_path();
    }
    searched += (searched.empty() ? "" : ", ") + ("<ancestors of " + binary.string() + ">/") +
                CRATERKIT_RELATIVE_DATA_DIR;
  }
  for (const auto& binary : binaries) {
    if (inside(binary, CRATERKIT_BUILD_DIR) && holds_data(CRATERKIT_SOURCE_DATA_DIR)) {
      return {fs::path(CRATERKIT_SOURCE_DATA_DIR), "source tree"};
    }
  }
  if (holds_data(CRATERKIT_INSTALL_DATA_DIR))
    return {fs::path(CRATERKIT_INSTALL_DATA_DIR), "configured prefix"};
  searched += std::string(searched.empty() ? "" : ", ") + CRATERKIT_INSTALL_DATA_DIR;
  throw std::runtime_error("craterkit data directory not found (looked in " + searched +
                           "): set CRATERKIT_DATA_DIR to the 'data' folder of craterkit");
}

// The environment variable is read on every call (a program or a Python session may set it late); the
// search is done once (a failure is not cached: the static's initialisation is retried).
std::pair<fs::path, std::string> located() {
  if (const char* env = std::getenv("CRATERKIT_DATA_DIR"); env != nullptr && *env != '\0') {
    std::error_code ec;
    if (!fs::is_directory(env, ec)) {
      throw std::runtime_error(std::string("CRATERKIT_DATA_DIR = '") + env +
                               "' is not a directory: point it at the 'data' folder of craterkit, or unset "
                               "it to use the installed data");
    }
    return {fs::path(env), "CRATERKIT_DATA_DIR"};
  }
  static const std::pair<fs::path, std::string> found = locate();
  return found;
}

}  // namespace

fs::path data_directory() {
  return located().first;
}

std::string data_directory_origin() {
  return located().second;
}

}  // namespace craterkit
