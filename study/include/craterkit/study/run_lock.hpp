#pragma once
// The claim on a run (docs/sweep.md, "Concurrency"): an advisory flock(LOCK_EX) on DIR/runs/<name>/lock, held
// by whoever runs the run for as long as it runs. The file is opened close-on-exec; the run's child process
// is given the descriptor explicitly (child_process.hpp), so that a sweep killed while its child runs leaves
// the lock held until the child ends, and no other child inherits it.
#include <filesystem>
#include <optional>

namespace craterkit::study {

class RunLock {
 public:
  // Takes the lock without waiting; nullopt when another open file description (another process, or this
  // one through another RunLock) holds it. std::runtime_error when the file cannot be opened or locked for
  // another reason (e.g. a file system without lock support).
  static std::optional<RunLock> try_acquire(const std::filesystem::path& lock_file);

  RunLock(RunLock&& other) noexcept;
  RunLock& operator=(RunLock&& other) noexcept;
  RunLock(const RunLock&) = delete;
  RunLock& operator=(const RunLock&) = delete;
  // Closes the descriptor: the lock is released unless a child process still holds the file description.
  ~RunLock();

  [[nodiscard]] int fd() const { return fd_; }

 private:
  explicit RunLock(int fd) : fd_(fd) {}
  int fd_ = -1;
};

// Whether someone holds the lock now (takes and releases it when free; false when the file is absent).
bool is_locked(const std::filesystem::path& lock_file);

}  // namespace craterkit::study
