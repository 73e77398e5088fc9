#pragma once
// A progress line on stderr for long commands without a simulation clock (`craterkit fit` on large
// tables), with the convention of `craterkit simulate`'s (docs/output.md): on a terminal one line redrawn in
// place a few times a second, in a log file or pipe one line every 10 s. Nothing is printed during the
// first second, so that quick commands stay silent, nor at all when disabled (--quiet).
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <string>

namespace craterkit::cli {

class ProgressLine {
 public:
  explicit ProgressLine(bool enabled, std::FILE* stream = stderr)
      : enabled_(enabled), stream_(stream), terminal_(::isatty(::fileno(stream)) == 1) {}
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;
  ~ProgressLine() { finish(); }

  // Shows `text` if it is time to (see above).
  void update(const std::string& text) {
    if (!enabled_) return;
    const double now = seconds();
    if (now < 1.0) return;
    if (drawn_ && now - last_ < (terminal_ ? 0.25 : 10.0)) return;
    if (terminal_) {
      std::fprintf(stream_, "\r%s\033[K", text.c_str());
    } else {
      std::fprintf(stream_, "%s\n", text.c_str());
    }
    std::fflush(stream_);
    drawn_ = true;
    last_ = now;
  }

  // Ends a line redrawn on a terminal, before other output.
  void finish() {
    if (enabled_ && drawn_ && terminal_) std::fprintf(stream_, "\n");
    drawn_ = false;
  }

  // Seconds since the line was made.
  [[nodiscard]] double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  bool enabled_;
  std::FILE* stream_;
  bool terminal_;
  bool drawn_ = false;
  double last_ = 0.0;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace craterkit::cli
