#pragma once
// An append-only CSV log whose rows carry the step at which they were written, resumable after a
// restart: opening it for a run resumed after `restart_step` completed steps keeps the header and every
// row with step <= restart_step byte for byte (rewritten atomically), drops later rows and an incomplete
// last line left by a killed run, then appends. The resumed log then equals the log of an uninterrupted
// run. A resumed log must hold what the checkpoint says it held (expected_rows, which the run saves with
// every checkpoint): a missing or truncated log is an error, not a silent new start. Used for ejecta.csv and
// crater_growth.csv (the conservation log has its own class with the same rules, conservation_log.hpp). Each
// row is flushed when written.
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

namespace craterkit::sph {

class StepCsvLog {
 public:
  // header: the header line without newline; step_column: index of the integer step column.
  // restart_step < 0: start a new log (truncating any old file). Throws craterkit::InputError naming
  // the file if a resumed file has another header or a malformed kept row, or, when expected_rows is
  // given, if it is missing or keeps another number of rows.
  StepCsvLog(std::filesystem::path csv, std::string header, std::size_t step_column,
             std::int64_t restart_step = -1, std::optional<std::uint64_t> expected_rows = std::nullopt);

  // One row (without newline), flushed.
  void append(const std::string& row);

  // The rows kept when resuming (without the header), split into columns: for rebuilding state.
  [[nodiscard]] const std::vector<std::vector<std::string>>& kept_rows() const { return kept_; }
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  // Rows below the header: kept and appended.
  [[nodiscard]] std::uint64_t rows() const { return rows_; }

 private:
  std::filesystem::path path_;
  std::ofstream out_;
  std::vector<std::vector<std::string>> kept_;
  std::uint64_t rows_ = 0;
};

}  // namespace craterkit::sph
