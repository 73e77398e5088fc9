#pragma once
// Figures drawn by the installed plotting scripts (scripts/plot_*.py) with /usr/bin/python3 and matplotlib.
#include <filesystem>
#include <string>
#include <vector>

namespace craterkit::cli {

// Runs /usr/bin/python3 with `args` (no shell); returns its exit status (128 when it did not exit normally).
int run_python(const std::vector<std::string>& args);

// The plotting script `name` (e.g. "plot_age.py"): the environment variable `override_variable` when set,
// else scripts/ beside the data directory (source tree), else scripts/ inside it (installation).
std::filesystem::path plot_script(const std::string& name, const char* override_variable);

// Empty when /usr/bin/python3, the script and matplotlib are there; otherwise why not, naming what is
// missing and how to get it.
std::string plotting_unavailable(const std::filesystem::path& script, const char* override_variable);

}  // namespace craterkit::cli
