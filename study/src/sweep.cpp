#include "craterkit/study/sweep.hpp"

#include <sched.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <set>
#include <thread>

#include <fmt/format.h>

namespace craterkit::study {

namespace {

using Clock = std::chrono::steady_clock;

void say(const SweepOptions& options, const std::string& line) {
  if (options.log != nullptr) *options.log << line << "\n" << std::flush;
}

void sleep_for(double seconds) {
  std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
}

std::string outcome_line(const RunRecord& r, double wall) {
  switch (r.status) {
    case RunStatus::done:
      return fmt::format("sweep: {}: done, crater radius {:.4g} +- {:.2g} m ({:.1f} s)", r.name,
                         r.result->row.crater_radius, r.result->row.crater_radius_sigma, wall);
    case RunStatus::no_crater:
      return fmt::format("sweep: {}: done, no crater found ({:.1f} s)", r.name, wall);
    case RunStatus::failed:
      return fmt::format("sweep: {}: FAILED, {} (see its failed.json and simulate.log)", r.name,
                         r.failure ? r.failure->description : "unknown");
    case RunStatus::interrupted:
      return fmt::format("sweep: {}: interrupted (resumed by the next sweep)", r.name);
    default:
      return fmt::format("sweep: {}: {}", r.name, to_string(r.status));
  }
}

std::optional<CostSample> cost_of(const RunResult& r) {
  if (!(r.cost_seconds > 0.0) || r.particles <= 0) return std::nullopt;
  return CostSample{r.cost_seconds, static_cast<double>(r.particles)};
}

}  // namespace

int available_cores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (::sched_getaffinity(0, sizeof(set), &set) == 0) return std::max(1, CPU_COUNT(&set));
  return std::max(1u, std::thread::hardware_concurrency());
}

int default_threads(int jobs) {
  return std::max(1, available_cores() / std::max(1, jobs));
}

SweepReport run_sweep(const StudyPlan& plan, const SweepOptions& options) {
  const std::size_t n = plan.runs.size();
  enum class State { pending, done, failed, given_up };
  std::vector<State> state(n, State::pending);
  std::vector<CostSample> costs;
  std::size_t done_before = 0, failed_before = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const auto dir = run_directory(plan.out, plan.runs[k].name);
    if (const auto result = read_result(dir)) {
      state[k] = State::done;
      ++done_before;
      if (const auto c = cost_of(*result)) costs.push_back(*c);
    } else if (!options.retry_failed && read_failure(dir)) {
      state[k] = State::failed;
      ++failed_before;
    }
  }
  say(options,
      fmt::format("sweep: {} runs in {}: {} finished before, {} failed before{}, {} to run; {} at once, "
                  "{} threads each",
                  n, plan.out.string(), done_before, failed_before,
                  failed_before > 0 ? " (skipped: --retry-failed runs them again)" : "",
                  n - done_before - failed_before, options.jobs, options.child.threads));

  SweepReport report;
  std::vector<Attempt> running;
  std::map<std::size_t, Clock::time_point> elsewhere;  // run -> when its claim was last tried
  std::set<std::size_t> retried;
  bool changed = true;
  const auto print_progress = [&] {
    ProgressCounts c;
    c.total = n;
    std::vector<RunningRun> going;
    std::vector<std::optional<double>> left;
    for (const auto& a : running) {
      const auto dir = run_directory(plan.out, plan.runs[a.run].name);
      going.push_back({std::chrono::duration<double>(Clock::now() - a.started).count(),
                       reported_particles(dir / "simulate.log", a.log_offset)});
    }
    for (std::size_t k = 0; k < n; ++k) {
      if (state[k] == State::done) ++c.done;
      if (state[k] == State::failed) ++c.failed;
      const bool here =
          std::any_of(running.begin(), running.end(), [&](const Attempt& a) { return a.run == k; });
      if ((state[k] == State::pending || state[k] == State::given_up) && !here) {
        left.emplace_back();
        if (!elsewhere.contains(k)) ++c.left;
      }
    }
    c.elsewhere = elsewhere.size();
    c.running = running.size() + c.elsewhere;
    say(options, progress_line(c, estimate_seconds_left(costs, going, left, options.jobs)));
    report.counts = c;
  };

  while (true) {
    for (std::size_t k = 0; k < n && static_cast<int>(running.size()) < options.jobs; ++k) {
      if (state[k] != State::pending) continue;
      if (std::any_of(running.begin(), running.end(), [&](const Attempt& a) { return a.run == k; })) continue;
      const auto seen = elsewhere.find(k);
      if (seen != elsewhere.end() &&
          std::chrono::duration<double>(Clock::now() - seen->second).count() < options.elsewhere_seconds) {
        continue;
      }
      const auto dir = run_directory(plan.out, plan.runs[k].name);
      auto lock = RunLock::try_acquire(dir / "lock");
      if (!lock) {
        if (seen == elsewhere.end()) {
          changed = true;
          say(options,
              fmt::format("sweep: {}: being run by another process; waiting for it", plan.runs[k].name));
        }
        elsewhere[k] = Clock::now();
        continue;
      }
      if (seen != elsewhere.end()) {
        elsewhere.erase(seen);
        changed = true;
      }
      // With the claim: the other process may have finished or failed the run meanwhile.
      if (const auto result = read_result(dir)) {
        state[k] = State::done;
        if (const auto c = cost_of(*result)) costs.push_back(*c);
        say(options, fmt::format("sweep: {}: finished by another process", plan.runs[k].name));
        changed = true;
        continue;
      }
      if (read_failure(dir)) {
        if (!options.retry_failed || retried.contains(k)) {
          state[k] = State::failed;
          say(options, fmt::format("sweep: {}: failed in another process", plan.runs[k].name));
          changed = true;
          continue;
        }
        std::filesystem::remove(dir / "failed.json");
        retried.insert(k);
      }
      running.push_back(start_attempt(plan, k, std::move(*lock), options.child));
      ++report.started;
      say(options, fmt::format("sweep: {}: started (attempt {}, process {})", plan.runs[k].name,
                               running.back().number, running.back().pid));
      changed = true;
    }
    if (changed) print_progress();
    changed = false;
    if (running.empty()) {
      const bool waiting =
          std::any_of(state.begin(), state.end(), [](State s) { return s == State::pending; });
      if (!waiting) break;
      sleep_for(options.elsewhere_seconds);  // only runs claimed elsewhere are left: wait for them
      continue;
    }
    sleep_for(options.poll_seconds);
    for (auto it = running.begin(); it != running.end();) {
      const auto status = poll_child(it->pid);
      if (!status) {
        ++it;
        continue;
      }
      const double wall = std::chrono::duration<double>(Clock::now() - it->started).count();
      const RunRecord record = finish_attempt(plan, *it, *status);
      say(options, outcome_line(record, wall));
      switch (record.status) {
        case RunStatus::done:
        case RunStatus::no_crater:
          state[it->run] = State::done;
          if (const auto c = cost_of(*record.result)) costs.push_back(*c);
          break;
        case RunStatus::failed:
          state[it->run] = State::failed;
          break;
        default:
          state[it->run] = State::given_up;  // interrupted: not started again by this sweep
      }
      it = running.erase(it);  // releases the claim
      changed = true;
    }
  }
  report.tables = collect(plan.out, options.producer);
  return report;
}

RunRecord run_task(const StudyPlan& plan, std::size_t index, const SweepOptions& options) {
  const PlannedRun& run = plan.runs.at(index);
  const auto dir = run_directory(plan.out, run.name);
  bool told = false;
  while (true) {
    if (read_result(dir)) {
      say(options, fmt::format("sweep: task {}: {}: finished before", index, run.name));
      return inspect_run(plan.out, run.name);
    }
    auto lock = RunLock::try_acquire(dir / "lock");
    if (!lock) {
      if (!told)
        say(options,
            fmt::format("sweep: task {}: {}: being run by another process; waiting", index, run.name));
      told = true;
      sleep_for(options.elsewhere_seconds);
      continue;
    }
    if (read_result(dir)) continue;  // finished meanwhile: reported above
    if (read_failure(dir)) {
      if (!options.retry_failed) {
        say(options,
            fmt::format("sweep: task {}: {}: failed before (--retry-failed runs it again)", index, run.name));
        RunRecord record = inspect_run(plan.out, run.name);
        record.status = RunStatus::failed;
        return record;
      }
      std::filesystem::remove(dir / "failed.json");
    }
    Attempt attempt = start_attempt(plan, index, std::move(*lock), options.child);
    say(options, fmt::format("sweep: task {}: {}: started (attempt {}, process {})", index, run.name,
                             attempt.number, attempt.pid));
    const ExitStatus status = wait_child(attempt.pid);
    const double wall = std::chrono::duration<double>(Clock::now() - attempt.started).count();
    const RunRecord record = finish_attempt(plan, attempt, status);
    say(options, outcome_line(record, wall));
    return record;
  }
}

}  // namespace craterkit::study
