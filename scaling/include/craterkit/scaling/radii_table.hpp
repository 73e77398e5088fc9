#pragma once
// Table of impacts and measured crater radii, the input of the scaling fit (docs/physics.md section 6,
// docs/architecture.md: "radii.csv -> Ceres fit").
//
// CSV with a header row naming the columns (any order, SI units, '#' starts a comment line):
//   impactor_radius, impactor_density, velocity, target_density, gravity, strength, crater_radius
// and optionally crater_radius_sigma (1-sigma of crater_radius, m). If that column is present every row
// must give a value > 0; rows are then weighted by it. Unknown columns are errors.
// Every bad cell is reported as InputError "<file>:<line>: column '<name>': <value> ... allowed ...":
// a missing column, a non-number, NaN/inf, a non-positive radius, density or velocity, a negative
// gravity or strength, a row with too few or too many cells, and a file without data rows.
#include <filesystem>
#include <istream>
#include <optional>
#include <string>
#include <vector>

#include "craterkit/scaling/point_source.hpp"

namespace craterkit::scaling {

struct ImpactRecord {
  Impactor impactor;
  Target target;
  double crater_radius = 0.0;                 // R, m (apparent radius at the pre-impact level)
  std::optional<double> crater_radius_sigma;  // 1-sigma of R, m
  int line = 0;                               // line number in the source file (1-based)
};

struct RadiiTable {
  std::string source;  // file name (for messages)
  std::vector<ImpactRecord> rows;
  bool has_sigma() const { return !rows.empty() && rows.front().crater_radius_sigma.has_value(); }
};

RadiiTable read_radii_csv(const std::filesystem::path& path);
RadiiTable parse_radii_csv(std::istream& in, const std::string& source_name);

// CSV text of a table (header + rows, full double precision), the inverse of parse_radii_csv.
std::string format_radii_csv(const RadiiTable& table);

}  // namespace craterkit::scaling
