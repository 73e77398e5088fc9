// CSV reader of the impacts-and-radii table (format in radii_table.hpp).
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/radii_table.hpp"

namespace craterkit::scaling {
namespace {

const std::vector<std::string>& required_columns() {
  static const std::vector<std::string> columns{"impactor_radius", "impactor_density", "velocity",
                                                "target_density",  "gravity",          "strength",
                                                "crater_radius"};
  return columns;
}
const std::string kSigmaColumn = "crater_radius_sigma";

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream stream(line);
  std::string cell;
  while (std::getline(stream, cell, ',')) cells.push_back(trim(cell));
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

std::string all_columns() {
  std::string out;
  for (const auto& name : required_columns()) out += name + ", ";
  return out + kSigmaColumn + " (optional)";
}

}  // namespace

RadiiTable parse_radii_csv(std::istream& in, const std::string& source_name) {
  RadiiTable table;
  table.source = source_name;
  std::map<std::string, std::size_t> index;  // column name -> position
  std::size_t column_count = 0;
  bool have_header = false;
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    const std::string content = trim(line);
    if (content.empty() || content.front() == '#') continue;
    const auto cells = split(content);
    const std::string where = source_name + ":" + std::to_string(line_number) + ": ";
    if (!have_header) {
      for (std::size_t i = 0; i < cells.size(); ++i) {
        const auto& name = cells[i];
        const bool known =
            name == kSigmaColumn ||
            std::find(required_columns().begin(), required_columns().end(), name) != required_columns().end();
        if (!known) {
          throw InputError(where + "header column " + std::to_string(i + 1) + " '" + name +
                           "' is not a known column; allowed: " + all_columns());
        }
        if (index.contains(name)) throw InputError(where + "header column '" + name + "' appears twice");
        index[name] = i;
      }
      for (const auto& name : required_columns()) {
        if (!index.contains(name)) {
          throw InputError(where + "header lacks the required column '" + name +
                           "'; required: " + all_columns());
        }
      }
      column_count = cells.size();
      have_header = true;
      continue;
    }
    if (cells.size() != column_count) {
      throw InputError(where + "row has " + std::to_string(cells.size()) + " cells but the header has " +
                       std::to_string(column_count) + " columns");
    }
    const auto cell = [&](const std::string& name, bool positive) -> double {
      const std::string& text = cells[index.at(name)];
      const std::string at = where + "column '" + name + "': ";
      if (text.empty()) throw InputError(at + "empty cell; a number is required");
      char* end = nullptr;
      errno = 0;
      const double value = std::strtod(text.c_str(), &end);
      if (end == text.c_str() || *end != '\0') throw InputError(at + "'" + text + "' is not a number");
      if (!std::isfinite(value))
        throw InputError(at + "'" + text + "' is not allowed: must be a finite number");
      if (positive && !(value > 0.0)) throw InputError(at + "'" + text + "' is not allowed: must be > 0");
      if (!positive && value < 0.0) throw InputError(at + "'" + text + "' is not allowed: must be >= 0");
      return value;
    };
    ImpactRecord row;
    row.line = line_number;
    row.impactor.radius = cell("impactor_radius", true);
    row.impactor.density = cell("impactor_density", true);
    row.impactor.velocity = cell("velocity", true);
    row.target.density = cell("target_density", true);
    row.target.gravity = cell("gravity", false);
    row.target.strength = cell("strength", false);
    row.crater_radius = cell("crater_radius", true);
    if (index.contains(kSigmaColumn)) row.crater_radius_sigma = cell(kSigmaColumn, true);
    table.rows.push_back(row);
  }
  if (!have_header) throw InputError(source_name + ": empty file; a header row and data rows are required");
  if (table.rows.empty()) throw InputError(source_name + ": no data rows after the header");
  return table;
}

RadiiTable read_radii_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot open the radii table for reading");
  return parse_radii_csv(in, path.string());
}

std::string format_radii_csv(const RadiiTable& table) {
  std::ostringstream out;
  out.precision(17);
  for (const auto& name : required_columns()) out << name << (name == "crater_radius" ? "" : ",");
  if (table.has_sigma()) out << "," << kSigmaColumn;
  out << "\n";
  for (const auto& row : table.rows) {
    out << row.impactor.radius << "," << row.impactor.density << "," << row.impactor.velocity << ","
        << row.target.density << "," << row.target.gravity << "," << row.target.strength << ","
        << row.crater_radius;
    if (table.has_sigma()) out << "," << row.crater_radius_sigma.value_or(0.0);
    out << "\n";
  }
  return out.str();
}

}  // namespace craterkit::scaling
