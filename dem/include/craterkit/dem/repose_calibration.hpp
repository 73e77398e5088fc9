#pragma once
// Contact friction from an angle of repose. A pile of spheres stands at an angle set by sliding and rolling
// friction together, with no closed form; craterkit measures it: quasi-static piles (column_collapse.hpp with
// a drag) at one sliding friction and several rolling frictions, tabulated in
// data/dem/repose_calibration.csv. The rolling friction for a wanted angle is read off that table
// (docs/dem.md, "Angle of repose").
#include <filesystem>
#include <vector>

namespace craterkit::dem {

struct ReposeCalibration {
  double sliding_friction = 0;           // the one mu_s of every pile in the table
  std::vector<double> rolling_friction;  // ascending
  std::vector<double> angle_degrees;     // the piles' flank angles, ascending with rolling_friction
};

// Reads the table: '#' comment lines, a header "sliding_friction,rolling_friction,angle_degrees", then rows.
// std::runtime_error naming file and line for a malformed row, a second sliding friction, rolling friction
// not ascending, or angles that do not rise with it (no unique inverse).
[[nodiscard]] ReposeCalibration read_repose_calibration(const std::filesystem::path& path);

// The shipped table (data/dem/repose_calibration.csv, found as every shipped data file is).
[[nodiscard]] ReposeCalibration shipped_repose_calibration();

// The rolling friction whose piles stand at this angle (linear between the table's rows). InputError naming
// the angle and the table's range when it lies outside it.
[[nodiscard]] double rolling_friction_for_repose_angle(const ReposeCalibration& table, double angle_degrees);

}  // namespace craterkit::dem
