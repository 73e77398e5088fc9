#pragma once
// conservation.csv: the conserved quantities (solver/conserved_quantities.hpp) of every step, one row per
// call to append(), with the header
//   time,step,mass,momentum_x,momentum_y,momentum_z,kinetic_energy,internal_energy,
//   potential_energy,total_energy,absolute_momentum
// numbers with 17 significant digits (exact round trip). A step log (step_csv_log.hpp): resumed after a
// restart it keeps the rows up to the restart step byte for byte, so it equals the log of an
// uninterrupted run.
#include <cstdint>
#include <filesystem>
#include <optional>

#include "craterkit/sph/io/step_csv_log.hpp"
#include "craterkit/sph/solver/conserved_quantities.hpp"

namespace craterkit::sph {

class ConservationLog {
 public:
  // Starts a new log (truncating any old file).
  explicit ConservationLog(const std::filesystem::path& csv);
  // Resumes the log of a run restarted after `restart_step` completed steps (StepCsvLog); a missing file
  // starts a new log.
  // With expected_rows, a missing log or one with another number of kept rows is an error.
  ConservationLog(const std::filesystem::path& csv, std::uint64_t restart_step,
                  std::optional<std::uint64_t> expected_rows = std::nullopt);

  void append(const ConservedQuantities& q);

  [[nodiscard]] const std::filesystem::path& path() const { return log_.path(); }
  [[nodiscard]] std::uint64_t rows() const { return log_.rows(); }
  static const char* header();  // the header line, without newline

 private:
  StepCsvLog log_;
};

}  // namespace craterkit::sph
