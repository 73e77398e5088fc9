#pragma once
// Table of impacts and measured crater radii, the input of the scaling fit (docs/physics.md section 6,
// docs/architecture.md: "radii.csv -> Ceres fit"; columns and checks in docs/scaling.md, "The fit").
//
// CSV with a header row naming the columns (any order, SI units, '#' starts a comment line, no quoting):
//   impactor_radius, impactor_density, velocity, target_density, gravity, strength, crater_radius
// (required) and optionally crater_radius_sigma (1-sigma of crater_radius, m). If that column is present
// every row must give a value > 0; rows are then weighted by it.
// Further columns, as `craterkit sweep` writes them after the fit's own:
//   run           information: the run's name (text, kept and reported)
//   growth_ended  information: true or false (whether the crater had stopped growing when measured)
//   anything else a grouping column (friction, porosity, resolution, A_low, impact.grading, ...): its values
//                 are kept as text, exactly as written, so "0.5" and "0.50" are different groups.
// A column name within 2 edits (case ignored) of a known column name other than `run` is refused with
// "did you mean": taken as a grouping column, a misspelt `strength` or `crater_radius_sigma` would silently
// change the fit (rows split into one-row groups, or unweighted). `run` is exempt because every name of up
// to 3 letters (rho, mu, ...) is within 2 edits of it.
// Every bad cell is reported as InputError "<file>:<line>: column '<name>': <value> ... allowed ...":
// a missing column (with "did you mean" when a header name is close to it), a repeated column, a
// non-number, NaN/inf, a non-positive radius, density or velocity, a negative gravity or strength, a
// growth_ended other than true/false, a row with too few or too many cells, and a file without data rows.
#include <cstdint>
#include <filesystem>
#include <functional>
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
  std::vector<std::string> group_values;      // one per RadiiTable::group_columns, as written
  std::optional<std::string> run;             // the run column, when the table has one
  std::optional<bool> growth_ended;           // the growth_ended column, when the table has one
};

struct RadiiTable {
  std::string source;  // file name (for messages)
  std::vector<ImpactRecord> rows;
  std::vector<std::string> group_columns;  // the grouping columns, in header order
  bool has_sigma() const { return !rows.empty() && rows.front().crater_radius_sigma.has_value(); }
  bool has_run() const { return !rows.empty() && rows.front().run.has_value(); }
  bool has_growth_ended() const { return !rows.empty() && rows.front().growth_ended.has_value(); }
};

// Names of the information columns.
inline constexpr const char* kRunColumn = "run";
inline constexpr const char* kGrowthEndedColumn = "growth_ended";

// Reading progress, for a progress line on large tables: bytes read of the whole, rows so far.
struct RadiiReadProgress {
  std::uint64_t bytes_read = 0;
  std::uint64_t bytes_total = 0;  // 0 when unknown
  std::size_t rows = 0;
};
using RadiiReadCallback = std::function<void(const RadiiReadProgress&)>;

// read_radii_csv counts the file's lines first, so that the rows are stored once, without the copies a
// growing array makes (a peak of twice the table's memory); `progress` is called every 65536 rows.
RadiiTable read_radii_csv(const std::filesystem::path& path, const RadiiReadCallback& progress = {});
RadiiTable parse_radii_csv(std::istream& in, const std::string& source_name, std::size_t expected_rows = 0,
                           const RadiiReadCallback& progress = {});

// CSV text of a table (header + rows, full double precision; grouping and information columns after the
// fit's own), the inverse of parse_radii_csv.
std::string format_radii_csv(const RadiiTable& table);

}  // namespace craterkit::scaling
