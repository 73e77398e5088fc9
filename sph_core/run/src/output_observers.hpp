#pragma once
// The run loop's own observers (run_simulation.hpp): the late-stage messages, the ejecta log, the
// conservation log and the snapshots. Private to the run layer.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "craterkit/sph/io/conservation_log.hpp"
#include "craterkit/sph/io/ejecta_csv.hpp"
#include "craterkit/sph/io/step_csv_log.hpp"
#include "craterkit/sph/run/run_observer.hpp"

namespace craterkit::sph {

// Says on stderr when the late-stage switch happens (with the Mach number just after it and the change of
// the time step) and, at the end, the largest Mach number since.
class LateStageReport final : public RunObserver {
 public:
  bool start(Simulation& simulation, const RunAttributes* checkpoint) override;
  bool after_step(Simulation& simulation) override;
  void finish(Simulation& simulation) override;

 private:
  bool was_late_ = false;
  double time_step_before_ = 0.0;
};

// The number of rows a resumed log must keep: the attribute `key` of the checkpoint, when present.
std::optional<std::uint64_t> expected_rows(const RunAttributes* checkpoint, const std::string& key);

// ejecta.csv: one row per ejected particle (solver/ejecta.hpp), resumable with the run; its row count
// travels in checkpoints as "ejecta_rows".
class EjectaLog final : public RunObserver {
 public:
  explicit EjectaLog(std::filesystem::path csv) : path_(std::move(csv)) {}
  bool start(Simulation& simulation, const RunAttributes* checkpoint) override;
  bool after_step(Simulation& simulation) override;
  void save(RunAttributes& checkpoint) const override;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::unique_ptr<StepCsvLog> log_;
};

// conservation.csv: the conserved quantities after every step (and at t = 0); its row count travels in
// checkpoints as "conservation_rows".
class ConservationRecorder final : public RunObserver {
 public:
  explicit ConservationRecorder(std::filesystem::path csv) : path_(std::move(csv)) {}
  bool start(Simulation& simulation, const RunAttributes* checkpoint) override;
  bool after_step(Simulation& simulation) override;
  void save(RunAttributes& checkpoint) const override;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::unique_ptr<ConservationLog> log_;
};

// snap_NNNNNN.h5 (+ XDMF sidecars and snapshots.xdmf) at the requested times, which the steps land on, and
// of the final state. Its place in the list of times travels in checkpoints as "next_snapshot".
class SnapshotWriter final : public RunObserver {
 public:
  SnapshotWriter(std::filesystem::path directory, std::vector<double> times, RunAttributes record,
                 int compression = 0)
      : directory_(std::move(directory)),
        times_(std::move(times)),
        record_(std::move(record)),
        compression_(compression) {}
  bool start(Simulation& simulation, const RunAttributes* checkpoint) override;
  bool after_step(Simulation& simulation) override;
  [[nodiscard]] double next_landing_time() const override;
  void save(RunAttributes& checkpoint) const override;
  void finish(Simulation& simulation) override;
  [[nodiscard]] const std::vector<std::string>& written() const { return written_; }

 private:
  void write(Simulation& simulation, std::size_t index);
  void write_due(Simulation& simulation);

  std::filesystem::path directory_;
  std::vector<double> times_;
  RunAttributes record_;
  int compression_ = 0;  // deflate level of the snapshots
  std::size_t next_ = 0;
  std::vector<std::string> written_;
};

// The attributes of a snapshot or checkpoint: the solver's state and the run record.
RunAttributes run_attributes(const Simulation& simulation, const RunAttributes& record);

}  // namespace craterkit::sph
