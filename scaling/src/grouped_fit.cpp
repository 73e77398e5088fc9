// One fit per group of a radii table, with each row's regime (see grouped_fit.hpp).
#include "craterkit/scaling/grouped_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>

#include "craterkit/common/input_error.hpp"

namespace craterkit::scaling {
namespace {

std::string join(const std::vector<std::string>& names) {
  if (names.empty()) return "(none)";
  std::string out;
  for (const auto& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

// Positions of group_by in the table's grouping columns, after checking the names.
std::vector<std::size_t> group_positions(const RadiiTable& table, const std::vector<std::string>& group_by) {
  std::vector<std::size_t> positions;
  std::set<std::string> seen;
  for (const auto& name : group_by) {
    const auto it = std::find(table.group_columns.begin(), table.group_columns.end(), name);
    if (it == table.group_columns.end()) {
      throw InputError("group-by column '" + name + "' is not a grouping column of " + table.source +
                       "; its grouping columns: " + join(table.group_columns));
    }
    if (!seen.insert(name).second) throw InputError("group-by column '" + name + "' is given twice");
    positions.push_back(static_cast<std::size_t>(it - table.group_columns.begin()));
  }
  return positions;
}

// The value as a number, if the whole text is one.
std::optional<double> as_number(const std::string& text) {
  if (text.empty()) return std::nullopt;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (*end != '\0' || !std::isfinite(value)) return std::nullopt;
  return value;
}

// A note for every grouping column in which one number is written two ways ("0.5" and "0.50"): such
// values are different groups, since they are compared as written.
void note_numbers_written_twice(const RadiiTable& table, const std::vector<std::size_t>& positions,
                                std::vector<std::string>& notes) {
  for (std::size_t position : positions) {
    std::map<double, std::string> first_text;
    std::set<std::string> reported;
    for (const auto& row : table.rows) {
      const std::string& text = row.group_values[position];
      const auto value = as_number(text);
      if (!value) continue;
      const auto [it, inserted] = first_text.emplace(*value, text);
      if (!inserted && it->second != text && reported.insert(text).second) {
        notes.push_back("column '" + table.group_columns[position] + "': '" + it->second + "' and '" + text +
                        "' are one number written two ways; they are fitted as separate groups (values "
                        "are compared as written)");
      }
    }
  }
}

std::vector<PooledColumn> pooled_columns(const RadiiTable& table, const std::vector<std::size_t>& positions) {
  std::vector<PooledColumn> out;
  for (std::size_t c = 0; c < table.group_columns.size(); ++c) {
    if (std::find(positions.begin(), positions.end(), c) != positions.end()) continue;
    PooledColumn pooled{table.group_columns[c], {}};
    std::set<std::string> seen;
    for (const auto& row : table.rows) {
      const auto& value = row.group_values[c];
      if (seen.insert(value).second) pooled.values.push_back(value);
    }
    out.push_back(pooled);
  }
  return out;
}

// The rows of one group that are fitted (indices into the table), and what is known of them before the fit.
GroupFit describe_rows(const RadiiTable& table, std::vector<std::uint32_t> rows) {
  GroupFit group;
  std::vector<double> strengths;
  strengths.reserve(rows.size());
  group.min_strength = std::numeric_limits<double>::infinity();
  group.max_strength = 0.0;
  group.lines.reserve(rows.size());
  for (const std::uint32_t index : rows) {
    const ImpactRecord& row = table.rows[index];
    group.lines.push_back(row.line);
    strengths.push_back(row.target.strength);
    group.min_strength = std::min(group.min_strength, row.target.strength);
    group.max_strength = std::max(group.max_strength, row.target.strength);
    if (row.growth_ended == false) group.growth_not_ended.push_back(row.line);
  }
  if (rows.empty()) group.min_strength = 0.0;
  std::sort(strengths.begin(), strengths.end());
  group.cohesions = static_cast<int>(std::unique(strengths.begin(), strengths.end()) - strengths.begin());
  group.rows = std::move(rows);
  return group;
}

void add_fit(GroupFit& group, const RadiiTable& table, const FitResult& fit) {
  group.regime_counts = count_regimes(table, group.rows, fit);
  group.fit = fit;
}

}  // namespace

std::string describe(const GroupKey& key) {
  if (key.empty()) return "all rows";
  std::string out;
  for (const auto& [column, value] : key) out += (out.empty() ? "" : ", ") + column + "=" + value;
  return out;
}

RowRegime row_regime(const ImpactRecord& row, const FitResult& fit) {
  Target target = row.target;
  if (const auto y = fit.strength()) target.strength = *y;
  RowRegime r;
  r.line = row.line;
  r.run = row.run;
  r.growth_ended = row.growth_ended;
  r.regime = regime(fit.law(), row.impactor, target);
  r.strength_to_gravity = r.regime.gravity_share > 0.0 ? r.regime.strength_share / r.regime.gravity_share
                                                       : std::numeric_limits<double>::infinity();
  return r;
}

std::vector<RowRegime> row_regimes(const std::vector<ImpactRecord>& rows, const FitResult& fit) {
  std::vector<RowRegime> out;
  out.reserve(rows.size());
  for (const auto& row : rows) out.push_back(row_regime(row, fit));
  return out;
}

namespace {

void count(RegimeKind kind, RegimeCounts& counts) {
  if (kind == RegimeKind::gravity) ++counts.gravity;
  if (kind == RegimeKind::strength) ++counts.strength;
  if (kind == RegimeKind::transitional) ++counts.transitional;
}

}  // namespace

RegimeCounts count_regimes(const std::vector<RowRegime>& regimes) {
  RegimeCounts counts;
  for (const auto& r : regimes) count(r.regime.kind, counts);
  return counts;
}

RegimeCounts count_regimes(const RadiiTable& table, std::span<const std::uint32_t> rows,
                           const FitResult& fit) {
  RegimeCounts counts;
  const ScalingLaw law = fit.law();
  const auto y = fit.strength();
  for (const std::uint32_t index : rows) {
    const ImpactRecord& row = table.rows[index];
    Target target = row.target;
    if (y) target.strength = *y;
    count(regime(law, row.impactor, target).kind, counts);
  }
  return counts;
}

GroupedFitResult fit_groups(const RadiiTable& table, const GroupedFitOptions& options) {
  GroupedFitResult result;
  result.source = table.source;
  result.form = options.fit.form;
  result.require_growth_ended = options.require_growth_ended;
  result.rows_read = static_cast<int>(table.rows.size());
  result.group_by = options.group_by.value_or(table.group_columns);
  const auto positions = group_positions(table, result.group_by);
  result.pooled = pooled_columns(table, positions);
  note_numbers_written_twice(table, positions, result.notes);
  if (options.require_growth_ended && !table.has_growth_ended()) {
    throw InputError(table.source + ": the table has no '" + std::string(kGrowthEndedColumn) +
                     "' column, so no row can be required to have ended its growth");
  }
  const int free_count = free_parameter_count(options.fit);

  // Rows by group (indices into the table, not copies), in order of first appearance; excluded rows still
  // make their group appear.
  if (table.rows.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw InputError(table.source + ": " + std::to_string(table.rows.size()) +
                     " rows; at most 4294967295 rows can be fitted");
  }
  std::vector<GroupKey> keys;
  std::map<GroupKey, std::size_t> key_index;
  std::vector<std::vector<std::uint32_t>> members;
  for (std::size_t i = 0; i < table.rows.size(); ++i) {
    const ImpactRecord& row = table.rows[i];
    GroupKey key;
    for (std::size_t k = 0; k < positions.size(); ++k)
      key.emplace_back(result.group_by[k], row.group_values[positions[k]]);
    auto [it, inserted] = key_index.emplace(std::move(key), keys.size());
    if (inserted) {
      keys.push_back(it->first);
      members.emplace_back();
    }
    if (options.require_growth_ended && row.growth_ended == false) {
      result.excluded.push_back(row.line);
      continue;
    }
    members[it->second].push_back(static_cast<std::uint32_t>(i));
  }

  for (std::size_t g = 0; g < keys.size(); ++g) {
    GroupFit group = describe_rows(table, std::move(members[g]));
    group.key = keys[g];
    const std::size_t rows = group.rows.size();
    if (!result.grouped()) {
      // One fit over everything: the single fit as `craterkit fit` has always done it, errors included.
      if (rows == 0) {
        throw InputError(table.source + ": every row has growth_ended = false; nothing is left to fit");
      }
      add_fit(group, table, fit_scaling_law(table, group.rows, options.fit));
    } else if (static_cast<int>(rows) <= free_count) {
      group.not_fitted = std::to_string(rows) + " rows for " + std::to_string(free_count) +
                         " free parameters; at least " + std::to_string(free_count + 1) +
                         " rows are required";
      if (rows == 0) group.not_fitted = "every row of the group has growth_ended = false";
    } else {
      try {
        add_fit(group, table, fit_scaling_law(table, group.rows, options.fit));
      } catch (const InputError&) {
        throw;  // bad data (file:line), not a property of the group
      } catch (const std::runtime_error& error) {
        group.not_fitted = error.what();  // every solve failed
      }
    }
    result.groups.push_back(std::move(group));
  }
  return result;
}

}  // namespace craterkit::scaling
