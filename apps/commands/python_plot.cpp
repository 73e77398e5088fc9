// Running the plotting scripts (python_plot.hpp).
#include "python_plot.hpp"

#include <cstdlib>
#include <stdexcept>

#include <sys/wait.h>
#include <unistd.h>

#include "craterkit/common/data_path.hpp"

namespace craterkit::cli {

int run_python(const std::vector<std::string>& args) {
  std::string python = "/usr/bin/python3";
  std::vector<std::string> copy = args;
  std::vector<char*> argv{python.data()};
  for (auto& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("cannot start /usr/bin/python3 (fork failed)");
  if (pid == 0) {
    execv(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) throw std::runtime_error("waiting for /usr/bin/python3 failed");
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

std::filesystem::path plot_script(const std::string& name, const char* override_variable) {
  if (const char* env = std::getenv(override_variable); env != nullptr && *env != '\0') return env;
  const auto data = data_directory();
  const auto beside = data.parent_path() / "scripts" / name;
  return std::filesystem::exists(beside) ? beside : data / "scripts" / name;
}

std::string plotting_unavailable(const std::filesystem::path& script, const char* override_variable) {
  if (!std::filesystem::exists("/usr/bin/python3")) {
    return "figures need /usr/bin/python3 with matplotlib, and /usr/bin/python3 does not exist";
  }
  if (!std::filesystem::exists(script)) {
    return "plotting script " + script.string() + " not found (set " + override_variable + " to scripts/" +
           script.filename().string() + ")";
  }
  if (run_python({"-c", "import matplotlib"}) != 0) {
    return "figures need matplotlib for /usr/bin/python3 (Debian: python3-matplotlib)";
  }
  return "";
}

}  // namespace craterkit::cli
