#include "craterkit/common/child_process.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

extern char** environ;

namespace craterkit {

std::string ExitStatus::describe() const {
  if (!signalled) return "exit status " + std::to_string(code);
  const char* name = ::strsignal(signal);
  return "killed by signal " + std::to_string(signal) +
         (name != nullptr ? std::string(" (") + name + ")" : "");
}

namespace {

// Frees the spawn attributes on every path out.
struct FileActions {
  posix_spawn_file_actions_t actions;
  FileActions() { posix_spawn_file_actions_init(&actions); }
  ~FileActions() { posix_spawn_file_actions_destroy(&actions); }
  FileActions(const FileActions&) = delete;
  FileActions& operator=(const FileActions&) = delete;
};

void check(int status, const char* what) {
  if (status != 0)
    throw std::runtime_error(std::string("posix_spawn: ") + what + ": " + std::strerror(status));
}

ExitStatus to_exit_status(int status) {
  ExitStatus out;
  if (WIFSIGNALED(status)) {
    out.signalled = true;
    out.signal = WTERMSIG(status);
  } else {
    out.code = WEXITSTATUS(status);
  }
  return out;
}

}  // namespace

pid_t spawn_child(const ChildCommand& command) {
  FileActions files;
  check(posix_spawn_file_actions_addopen(&files.actions, 0, "/dev/null", O_RDONLY, 0), "stdin");
  check(posix_spawn_file_actions_addopen(&files.actions, 1, command.stdout_file.c_str(),
                                         O_WRONLY | O_CREAT | O_TRUNC, 0644),
        "stdout");
  check(posix_spawn_file_actions_addopen(&files.actions, 2, command.stderr_file.c_str(),
                                         O_WRONLY | O_CREAT | O_APPEND, 0644),
        "stderr");
  // dup2 of a descriptor onto itself clears its close-on-exec flag in the child (POSIX 2024; glibc >= 2.29).
  for (const int fd : command.inherited_fds)
    check(posix_spawn_file_actions_adddup2(&files.actions, fd, fd), "dup2");
  std::vector<std::string> storage;
  storage.push_back(command.program.string());
  storage.insert(storage.end(), command.arguments.begin(), command.arguments.end());
  std::vector<char*> argv;
  for (auto& s : storage) argv.push_back(s.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  check(posix_spawn(&pid, command.program.c_str(), &files.actions, nullptr, argv.data(), environ),
        command.program.c_str());
  return pid;
}

std::optional<ExitStatus> poll_child(pid_t pid) {
  int status = 0;
  while (true) {
    const pid_t r = ::waitpid(pid, &status, WNOHANG);
    if (r == 0) return std::nullopt;
    if (r == pid) return to_exit_status(status);
    if (errno == EINTR) continue;
    throw std::runtime_error("waitpid " + std::to_string(pid) + ": " + std::strerror(errno));
  }
}

ExitStatus wait_child(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) != pid) {
    if (errno != EINTR)
      throw std::runtime_error("waitpid " + std::to_string(pid) + ": " + std::strerror(errno));
  }
  return to_exit_status(status);
}

}  // namespace craterkit
