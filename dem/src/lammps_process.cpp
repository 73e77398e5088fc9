#include "craterkit/dem/lammps_process.hpp"

#include <fmt/format.h>

#include <signal.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <thread>

#include "craterkit/common/child_process.hpp"

namespace craterkit::dem {

namespace {

std::filesystem::path on_path(std::string_view name) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return {};
  std::stringstream folders(path);
  std::string folder;
  while (std::getline(folders, folder, ':')) {
    if (folder.empty()) continue;
    const auto candidate = std::filesystem::path(folder) / name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return {};
}

// The first line of the log that starts with "ERROR", with the line after it (LAMMPS puts the command that
// failed there), or "" when there is none.
std::string error_in_log(const std::filesystem::path& log) {
  std::ifstream in(log);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("ERROR", 0) == 0) {
      std::string next;
      if (std::getline(in, next) && next.rfind("Last command:", 0) == 0) line += "; " + next;
      return line;
    }
  }
  return {};
}

// The last non-empty line a failed program wrote to its error file (mpirun says there why it did not start).
std::string last_line_of(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line, last;
  while (std::getline(in, line))
    if (line.find_first_not_of(" \t") != std::string::npos) last = line;
  return last;
}

}  // namespace

std::filesystem::path find_lammps() {
  if (const char* chosen = std::getenv("CRATERKIT_LAMMPS"); chosen != nullptr && *chosen != '\0') {
    std::filesystem::path program(chosen);
    if (program.is_relative() && program.filename() == program) program = on_path(chosen);
    if (program.empty() || ::access(program.c_str(), X_OK) != 0)
      throw std::runtime_error(fmt::format("CRATERKIT_LAMMPS={}: not an executable program", chosen));
    return program;
  }
  auto program = on_path("lmp");
  if (program.empty())
    throw std::runtime_error(
        "LAMMPS not found: no `lmp` on PATH (Debian: apt-get install lammps, or scripts/install-deps; or set "
        "CRATERKIT_LAMMPS to the executable)");
  return program;
}

void run_lammps(const LammpsRun& run, const LammpsPoll& poll) {
  if (run.processes < 1)
    throw std::invalid_argument(fmt::format("run_lammps: processes {} < 1", run.processes));
  const auto lammps = find_lammps();
  const auto log = run.folder / (std::filesystem::path(run.script_name).stem().string() + ".log");
  ChildCommand command;
  std::vector<std::string> lammps_arguments = {"-in",     run.script_name, "-log",   log.filename().string(),
                                               "-screen", "none",          "-nocite"};
  if (run.processes == 1) {
    command.program = lammps;
    command.arguments = lammps_arguments;
  } else {
    command.program = on_path("mpirun");
    if (command.program.empty())
      throw std::runtime_error("LAMMPS over several processes needs mpirun (Debian: openmpi-bin)");
    command.arguments = {"-n", std::to_string(run.processes), lammps.string()};
    command.arguments.insert(command.arguments.end(), lammps_arguments.begin(), lammps_arguments.end());
  }
  command.stdout_file = run.folder / "lammps.out";
  command.stderr_file = run.folder / "lammps.err";
  // posix_spawn cannot portably start the child in another folder; `env -C folder` does (coreutils).
  ChildCommand in_folder = command;
  in_folder.program = "/usr/bin/env";
  in_folder.arguments = {"-C", run.folder.string(), command.program.string()};
  in_folder.arguments.insert(in_folder.arguments.end(), command.arguments.begin(), command.arguments.end());
  const pid_t child = spawn_child(in_folder);
  ExitStatus status;
  if (!poll.call) {
    status = wait_child(child);
  } else {
    using Clock = std::chrono::steady_clock;
    auto next_poll = Clock::now() + std::chrono::duration_cast<Clock::duration>(poll.interval);
    for (;;) {
      if (const auto ended = poll_child(child)) {
        status = *ended;
        break;
      }
      if (Clock::now() >= next_poll) {
        try {
          poll.call();
        } catch (...) {
          ::kill(child, SIGTERM);
          wait_child(child);
          throw;
        }
        next_poll = Clock::now() + std::chrono::duration_cast<Clock::duration>(poll.interval);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  }
  if (!status.success()) {
    std::string reason = error_in_log(log);
    if (reason.empty()) {
      reason = fmt::format("{} ended with {}", command.program.filename().string(), status.describe());
      if (const std::string said = last_line_of(command.stderr_file); !said.empty()) reason += ": " + said;
    }
    throw std::runtime_error(fmt::format("LAMMPS run {} failed: {} (log {})",
                                         (run.folder / run.script_name).string(), reason, log.string()));
  }
}

std::vector<double> last_thermo_values(const std::filesystem::path& log, std::size_t columns) {
  std::ifstream in(log);
  std::string line;
  std::vector<double> last, values(columns);
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::size_t read = 0;
    while (read < columns && words >> values[read]) ++read;
    std::string more;
    if (read == columns && !(words >> more)) last = values;
  }
  return last;
}

}  // namespace craterkit::dem
