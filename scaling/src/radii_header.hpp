#pragma once
// The header row of a radii table (radii_table.hpp): which column is which, and the checks that keep a
// misspelt column from becoming a grouping column (docs/scaling.md, "Columns").
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace craterkit::scaling::detail {

const std::vector<std::string>& required_radii_columns();
inline constexpr const char* kSigmaColumn = "crater_radius_sigma";

// Levenshtein distance with ASCII case ignored (insertions, deletions and substitutions cost 1).
std::size_t edit_distance(std::string_view a, std::string_view b);

struct RadiiHeader {
  std::map<std::string, std::size_t> fit_columns;  // required columns and crater_radius_sigma -> position
  std::optional<std::size_t> run;                  // position of `run`
  std::optional<std::size_t> growth_ended;         // position of `growth_ended`
  std::vector<std::string> group_columns;          // every other column, in header order
  std::vector<std::size_t> group_positions;        // their positions
  std::size_t column_count = 0;
};

// Classifies the header cells; InputError prefixed by `where` ("<file>:<line>: ") for an empty or
// repeated name, a missing required column, or an extra name within 2 edits of a known one.
RadiiHeader parse_radii_header(const std::vector<std::string>& cells, const std::string& where);

}  // namespace craterkit::scaling::detail
