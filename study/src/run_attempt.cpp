#include "craterkit/study/run_attempt.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <csignal>
#include <ctime>
#include <deque>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "craterkit/common/atomic_file.hpp"

namespace craterkit::study {

namespace {

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  ::gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof(name) - 1) != 0) return "unknown";
  return name;
}

// Appends one line with a single write (O_APPEND), so lines of several processes do not interleave.
void append_line(const std::filesystem::path& file, const std::string& line) {
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error("cannot append to " + file.string());
  const ssize_t written = ::write(fd, line.data(), line.size());
  ::close(fd);
  if (written != static_cast<ssize_t>(line.size()))
    throw std::runtime_error("cannot append to " + file.string());
}

std::optional<std::string> read_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string read_from(const std::filesystem::path& file, std::uintmax_t offset) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return "";
  in.seekg(static_cast<std::streamoff>(offset));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::string> last_lines(const std::string& text, std::size_t count) {
  std::deque<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    lines.push_back(line);
    if (lines.size() > count) lines.pop_front();
  }
  return {lines.begin(), lines.end()};
}

}  // namespace

Attempt start_attempt(const StudyPlan& plan, std::size_t run, RunLock lock, const ChildSettings& child) {
  const PlannedRun& planned = plan.runs.at(run);
  const auto dir = run_directory(plan.out, planned.name);
  const int number = count_attempts(dir) + 1;
  const std::string when = utc_now(), host = host_name();
  append_line(dir / "attempts.log",
              fmt::format("attempt {} started {} on {} by process {}\n", number, when, host, ::getpid()));
  const auto log = dir / "simulate.log";
  append_line(log, fmt::format("=== craterkit sweep: attempt {} of run {}, {} on {} ===\n", number,
                               planned.name, when, host));
  std::error_code ec;
  const auto offset = std::filesystem::file_size(log, ec);
  ChildCommand command;
  command.program = child.program;
  command.arguments = {"simulate",  (dir / "config.toml").string(), "--out",    dir.string(),
                       "--threads", std::to_string(child.threads),  "--resume", "--json",
                       "--quiet"};
  command.stdout_file = dir / "simulate.out.json";
  command.stderr_file = log;
  command.inherited_fds = {lock.fd()};
  const pid_t pid = spawn_child(command);
  return Attempt{run, std::move(lock), pid, number, std::chrono::steady_clock::now(), ec ? 0 : offset};
}

RunRecord finish_attempt(const StudyPlan& plan, const Attempt& attempt, const ExitStatus& status) {
  const PlannedRun& planned = plan.runs.at(attempt.run);
  const auto dir = run_directory(plan.out, planned.name);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - attempt.started).count();
  std::string message;
  if (status.success()) {
    const auto summary = read_file(dir / "simulate.out.json");
    const auto crater = read_file(dir / "crater.json");
    if (summary && crater) {
      try {
        write_text_atomically(dir / "result.json",
                              make_result_json(plan, planned, *summary, *crater, wall, attempt.number));
        std::error_code ignored;
        std::filesystem::remove(dir / "failed.json", ignored);
        return inspect_run(plan.out, planned.name);
      } catch (const std::runtime_error& e) {
        message = e.what();
      }
    } else {
      message = "the run ended with exit status 0 but without its summary or crater.json";
    }
  } else if (status.signalled &&
             (status.signal == SIGINT || status.signal == SIGTERM || status.signal == SIGHUP)) {
    RunRecord record = inspect_run(plan.out, planned.name);
    record.status = RunStatus::interrupted;
    return record;
  }
  const auto tail = last_lines(read_from(dir / "simulate.log", attempt.log_offset), 20);
  write_text_atomically(dir / "failed.json",
                        make_failure_json(planned.name, status, attempt.number, wall, tail, message));
  RunRecord record = inspect_run(plan.out, planned.name);
  record.status = RunStatus::failed;  // the lock is still ours, so inspect_run saw it as running
  return record;
}

std::optional<double> reported_particles(const std::filesystem::path& log, std::uintmax_t offset) {
  const std::string text = read_from(log, offset);
  const std::string marker = "impact: particles ";
  const auto at = text.find(marker);
  if (at == std::string::npos) return std::nullopt;
  try {
    return std::stod(text.substr(at + marker.size(), 20));
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

}  // namespace craterkit::study
