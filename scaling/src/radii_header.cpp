// Header of the radii table: fit, information and grouping columns (see radii_header.hpp).
#include "radii_header.hpp"

#include <algorithm>
#include <cctype>

#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/radii_table.hpp"

namespace craterkit::scaling::detail {
namespace {

// A grouping column closer than this to a known name is taken for a misspelling of it.
constexpr std::size_t kNearEdits = 2;

std::string all_columns() {
  std::string out;
  for (const auto& name : required_radii_columns()) out += name + ", ";
  return out + kSigmaColumn + " (optional); information columns " + kRunColumn + ", " + kGrowthEndedColumn +
         "; any other column groups the rows";
}

bool is_known(const std::string& name) {
  const auto& required = required_radii_columns();
  return name == kSigmaColumn || name == kRunColumn || name == kGrowthEndedColumn ||
         std::find(required.begin(), required.end(), name) != required.end();
}

// The known names a misspelling is looked for against: every one but `run`, which is within 2 edits of
// every name of up to 3 letters (rho, mu, ...).
std::vector<std::string> checked_names() {
  std::vector<std::string> names = required_radii_columns();
  names.emplace_back(kSigmaColumn);
  names.emplace_back(kGrowthEndedColumn);
  return names;
}

// The known name within kNearEdits of `name`, nearest first; empty when none is.
std::optional<std::string> near_known_name(const std::string& name) {
  std::optional<std::string> best;
  std::size_t best_distance = kNearEdits + 1;
  for (const auto& known : checked_names()) {
    const std::size_t distance = edit_distance(name, known);
    if (distance < best_distance) {
      best = known;
      best_distance = distance;
    }
  }
  return best;
}

}  // namespace

const std::vector<std::string>& required_radii_columns() {
  static const std::vector<std::string> columns{"impactor_radius", "impactor_density", "velocity",
                                                "target_density",  "gravity",          "strength",
                                                "crater_radius"};
  return columns;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  const auto lower = [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); };
  std::vector<std::size_t> previous(b.size() + 1), current(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) previous[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t substitution = previous[j - 1] + (lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
    }
    std::swap(previous, current);
  }
  return previous[b.size()];
}

RadiiHeader parse_radii_header(const std::vector<std::string>& cells, const std::string& where) {
  RadiiHeader header;
  header.column_count = cells.size();
  std::map<std::string, std::size_t> seen;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (cells[i].empty()) {
      throw InputError(where + "header column " + std::to_string(i + 1) +
                       " has no name; every column needs one (allowed: " + all_columns() + ")");
    }
    if (seen.contains(cells[i])) throw InputError(where + "header column '" + cells[i] + "' appears twice");
    seen[cells[i]] = i;
  }
  // A missing required column first, pointing at a header name close to it.
  for (const auto& name : required_radii_columns()) {
    if (seen.contains(name)) continue;
    std::string hint;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (!is_known(cells[i]) && edit_distance(cells[i], name) <= kNearEdits) {
        hint = " (did you mean '" + name + "' for header column " + std::to_string(i + 1) + " '" + cells[i] +
               "'?)";
        break;
      }
    }
    throw InputError(where + "header lacks the required column '" + name + "'" + hint +
                     "; columns: " + all_columns());
  }
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const std::string& name = cells[i];
    if (name == kRunColumn) {
      header.run = i;
    } else if (name == kGrowthEndedColumn) {
      header.growth_ended = i;
    } else if (is_known(name)) {
      header.fit_columns[name] = i;
    } else if (const auto near = near_known_name(name)) {
      throw InputError(where + "header column " + std::to_string(i + 1) + " '" + name + "' is within " +
                       std::to_string(kNearEdits) + " edits of the column name '" + *near +
                       "': did you mean '" + *near +
                       "'? A column this close to a known name is refused rather than taken as a grouping "
                       "column; rename it if it is one");
    } else {
      header.group_columns.push_back(name);
      header.group_positions.push_back(i);
    }
  }
  return header;
}

}  // namespace craterkit::scaling::detail
