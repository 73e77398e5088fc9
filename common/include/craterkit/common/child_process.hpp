#pragma once
// A child process (posix_spawn): stdin from /dev/null, stdout into a file (not a pipe, so that
// the child outlives a killed parent without a broken pipe), stderr appended to a log, and exactly the
// descriptors it is given kept open (their close-on-exec flag cleared in the child only).
#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace craterkit {

struct ChildCommand {
  std::filesystem::path program;
  std::vector<std::string> arguments;  // after argv[0]
  std::filesystem::path stdout_file;   // truncated
  std::filesystem::path stderr_file;   // appended
  std::vector<int> inherited_fds;      // kept open in the child (the run's lock)
};

struct ExitStatus {
  bool signalled = false;
  int code = 0;    // exit status when not signalled
  int signal = 0;  // the signal when signalled
  [[nodiscard]] bool success() const { return !signalled && code == 0; }
  [[nodiscard]] std::string describe() const;  // "exit status 2", "killed by signal 9 (Killed)"
};

// Starts the child; std::runtime_error when it cannot be started.
pid_t spawn_child(const ChildCommand& command);
// The child's exit status once it has ended (reaping it), nullopt while it runs.
std::optional<ExitStatus> poll_child(pid_t pid);
ExitStatus wait_child(pid_t pid);

}  // namespace craterkit
