#include "output_observers.hpp"

#include <cstdio>

#include "craterkit/sph/io/solver_state.hpp"
#include "craterkit/sph/io/xdmf.hpp"

namespace craterkit::sph {

RunAttributes run_attributes(const Simulation& simulation, const RunAttributes& record) {
  RunAttributes a = record;
  write_solver_state(simulation.state(), a);
  return a;
}

bool LateStageReport::start(Simulation& simulation, const RunAttributes*) {
  was_late_ = simulation.late_stage_active();
  time_step_before_ = simulation.next_time_step();
  return false;
}

bool LateStageReport::after_step(Simulation& simulation) {
  if (!was_late_ && simulation.late_stage_active()) {
    std::fprintf(
        stderr,
        "\nlate stage: switched to the low-sound-speed medium at t = %.6g s (step %llu), A_low = %.6g "
        "Pa; largest Mach number |v|/c just after the switch %.4g; time step %.4g s -> %.4g s\n",
        simulation.time(), static_cast<unsigned long long>(simulation.step_count()),
        simulation.problem().late_stage.A_low[0], simulation.mach_at_transition(), time_step_before_,
        simulation.next_time_step());
  }
  was_late_ = simulation.late_stage_active();
  time_step_before_ = simulation.next_time_step();
  return false;
}

void LateStageReport::finish(Simulation& simulation) {
  if (!simulation.late_stage_active()) return;
  std::fprintf(stderr, "late stage: largest Mach number |v|/c since the switch %.4g (at the switch %.4g)\n",
               simulation.late_stage_max_mach(), simulation.mach_at_transition());
}

std::optional<std::uint64_t> expected_rows(const RunAttributes* checkpoint, const std::string& key) {
  if (checkpoint == nullptr) return std::nullopt;
  const auto found = checkpoint->numbers.find(key);
  if (found == checkpoint->numbers.end() || !(found->second >= 0.0)) return std::nullopt;
  return static_cast<std::uint64_t>(found->second);
}

// Over several processes process 0 receives every ejection (Simulation::take_new_ejecta) and writes.
bool EjectaLog::start(Simulation& simulation, const RunAttributes* checkpoint) {
  if (!simulation.writes_output()) return false;
  const std::int64_t restart_step =
      checkpoint != nullptr ? static_cast<std::int64_t>(simulation.step_count()) : -1;
  log_ = std::make_unique<StepCsvLog>(path_, ejecta_csv_header(), ejecta_csv_step_column, restart_step,
                                      expected_rows(checkpoint, "ejecta_rows"));
  return false;
}

void EjectaLog::save(RunAttributes& checkpoint) const {
  if (log_) checkpoint.numbers["ejecta_rows"] = static_cast<double>(log_->rows());
}

bool EjectaLog::after_step(Simulation& simulation) {
  auto scope = simulation.timers().measure("output");
  for (const auto& record : simulation.take_new_ejecta()) {
    if (log_) log_->append(ejecta_csv_row(record));
  }
  return false;
}

// Over several processes every one sums its share (conserved() is collective); process 0 writes.
bool ConservationRecorder::start(Simulation& simulation, const RunAttributes* checkpoint) {
  if (checkpoint != nullptr) {
    if (simulation.writes_output()) {
      log_ = std::make_unique<ConservationLog>(path_, simulation.step_count(),
                                               expected_rows(checkpoint, "conservation_rows"));
    }
  } else {
    const ConservedQuantities initial = simulation.conserved();
    if (simulation.writes_output()) {
      log_ = std::make_unique<ConservationLog>(path_);
      log_->append(initial);
    }
  }
  return false;
}

bool ConservationRecorder::after_step(Simulation& simulation) {
  auto scope = simulation.timers().measure("output");
  const ConservedQuantities now = simulation.conserved();
  if (log_) log_->append(now);
  return false;
}

void ConservationRecorder::save(RunAttributes& checkpoint) const {
  if (log_) checkpoint.numbers["conservation_rows"] = static_cast<double>(log_->rows());
}

bool SnapshotWriter::start(Simulation& simulation, const RunAttributes* checkpoint) {
  if (checkpoint != nullptr) {
    next_ =
        static_cast<std::size_t>(checkpoint->number("next_snapshot", directory_.string() + "/checkpoint.h5"));
  } else {
    write_due(simulation);  // t = 0 (and any requested time already reached)
  }
  return false;
}

bool SnapshotWriter::after_step(Simulation& simulation) {
  write_due(simulation);
  return false;
}

double SnapshotWriter::next_landing_time() const {
  return next_ < times_.size() ? times_[next_] : RunObserver::next_landing_time();
}

void SnapshotWriter::save(RunAttributes& checkpoint) const {
  checkpoint.numbers["next_snapshot"] = static_cast<double>(next_);
}

void SnapshotWriter::finish(Simulation& simulation) {
  // The final state, unless a snapshot was just written at this time.
  const bool written = !times_.empty() && next_ > 0 && times_[next_ - 1] == simulation.time();
  if (!written) write(simulation, std::max(next_, times_.size()));
}

void SnapshotWriter::write_due(Simulation& simulation) {
  while (next_ < times_.size() && times_[next_] <= simulation.time()) write(simulation, next_++);
}

void SnapshotWriter::write(Simulation& simulation, std::size_t index) {
  auto scope = simulation.timers().measure("output");
  char name[32];
  std::snprintf(name, sizeof name, "snap_%06zu.h5", index);
  Particles gathered;
  const Particles& whole = simulation.whole_particles(gathered);  // collective over several processes
  if (!simulation.writes_output()) return;
  write_snapshot(directory_ / name, whole, run_attributes(simulation, record_), compression_);
  write_time_series_xdmf(directory_ / "snapshots.xdmf", find_snapshots(directory_));
  written_.push_back((directory_ / name).string());
}

}  // namespace craterkit::sph
