#pragma once
// One fit of the point-source law per group of a radii table (docs/scaling.md, "Fitting a sweep: one fit
// per group"). A sweep table (`craterkit sweep`) varies impactor size and cohesion, and also material or
// numerical parameters (friction, porosity, resolution, ...) that the law does not contain; the rows that
// share those values belong to one law, so each group is fitted on its own, with all its sizes and
// cohesions together. Each row of a fitted group gets its regime under the fitted law.
//
// Regime of a row: the share of the gravity and the strength term inside the braces of the law (the same
// in both forms, docs/physics.md section 6), as `scaling::regime` gives it: gravity when the gravity term
// is at least 0.9 of the sum (strength/gravity ratio <= 1/9), strength when the strength term is (ratio
// >= 9), transitional in between. These are the thresholds `craterkit scale` reports with, so that a word
// means the same in every command. With a shared Y the row's strength is the fitted Y.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "craterkit/scaling/fit.hpp"
#include "craterkit/scaling/point_source.hpp"
#include "craterkit/scaling/radii_table.hpp"

namespace craterkit::scaling {

struct GroupedFitOptions {
  FitOptions fit;  // the same options for every group
  // Grouping columns to fit separately: empty = every grouping column of the table; an empty list = one
  // fit over all rows (`--group-by none`). Names must be grouping columns of the table.
  std::optional<std::vector<std::string>> group_by;
  // Leave out the rows with growth_ended = false (the table must have that column); by default they are
  // fitted and flagged.
  bool require_growth_ended = false;
};

struct RowRegime {
  int line = 0;
  std::optional<std::string> run;    // the table's run column, when present
  std::optional<bool> growth_ended;  // the table's growth_ended column, when present
  Regime regime;                     // kind and shares under the fitted law
  double strength_to_gravity = 0.0;  // strength term / gravity term (+inf without gravity)
};

struct RegimeCounts {
  int gravity = 0;
  int transitional = 0;
  int strength = 0;
};

using GroupKey = std::vector<std::pair<std::string, std::string>>;  // (column, value as written)

struct GroupFit {
  GroupKey key;                       // in group_by order; empty for one fit over everything
  std::vector<int> lines;             // table lines of the rows fitted (after any exclusion)
  std::vector<std::uint32_t> rows;    // their indices in the table's rows
  int cohesions = 0;                  // distinct strengths among them
  double min_strength = 0.0;          // their range, Pa
  double max_strength = 0.0;          //
  std::vector<int> growth_not_ended;  // lines fitted although flagged growth_ended = false
  std::optional<FitResult> fit;       // empty when the group could not be fitted
  std::string not_fitted;             // why, when fit is empty
  // The rows' regimes under the fitted law, counted (row_regimes() gives them row by row, and
  // `craterkit fit --residuals` writes them per row).
  RegimeCounts regime_counts;
};

struct PooledColumn {
  std::string name;                 // a grouping column not in group_by
  std::vector<std::string> values;  // its distinct values, in order of appearance
};

struct GroupedFitResult {
  std::string source;
  Form form = Form::holsapple;
  std::vector<std::string> group_by;  // columns fitted separately; empty: one fit over all rows
  std::vector<PooledColumn> pooled;   // grouping columns whose values were fitted together
  int rows_read = 0;
  bool require_growth_ended = false;
  std::vector<int> excluded;       // lines left out by require_growth_ended
  std::vector<std::string> notes;  // e.g. one number written two ways in a grouping column
  std::vector<GroupFit> groups;    // in order of first appearance in the table
  bool grouped() const { return !group_by.empty(); }
};

// Fits every group. Throws InputError for a group_by name that is not a grouping column (naming the
// table's grouping columns), a repeated one, require_growth_ended without a growth_ended column, bad fit
// options, and (when not grouped) everything fit_scaling_law throws. A group with no more rows than free
// parameters, or whose solves all fail, is reported with not_fitted instead.
GroupedFitResult fit_groups(const RadiiTable& table, const GroupedFitOptions& options);

// Regime of each of `rows` under the fitted law (the fitted Y for a shared strength).
std::vector<RowRegime> row_regimes(const std::vector<ImpactRecord>& rows, const FitResult& fit);
RowRegime row_regime(const ImpactRecord& row, const FitResult& fit);
RegimeCounts count_regimes(const std::vector<RowRegime>& regimes);
// The regimes of the table's rows at `rows` under the fitted law, counted without keeping them.
RegimeCounts count_regimes(const RadiiTable& table, std::span<const std::uint32_t> rows,
                           const FitResult& fit);

// "friction=0.55, porosity=0.5"; "all rows" for an empty key.
std::string describe(const GroupKey& key);

}  // namespace craterkit::scaling
