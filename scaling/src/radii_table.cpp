// CSV reader and writer of the impacts-and-radii table (format in radii_table.hpp; the header in
// radii_header.hpp).
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/radii_table.hpp"
#include "radii_header.hpp"

namespace craterkit::scaling {
namespace {

using detail::kSigmaColumn;

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  const auto last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

// The trimmed cells of a line into `cells` (reused from line to line: no allocation per row once the
// cells' strings have grown).
void split(const std::string& line, std::vector<std::string>& cells) {
  std::size_t count = 0, start = 0;
  while (true) {
    const std::size_t comma = std::min(line.find(',', start), line.size());
    if (count == cells.size()) cells.emplace_back();
    const auto first = line.find_first_not_of(" \t\r", start);
    if (first == std::string::npos || first >= comma) {
      cells[count].clear();
    } else {
      const auto last = line.find_last_not_of(" \t\r", comma - 1);
      cells[count].assign(line, first, last - first + 1);
    }
    ++count;
    if (comma == line.size()) break;
    start = comma + 1;
  }
  cells.resize(count);
}

// One data row: the fit's numbers with their checks, then the information and grouping cells.
ImpactRecord parse_row(const std::vector<std::string>& cells, const detail::RadiiHeader& header,
                       const std::string& where) {
  const auto cell = [&](const std::string& name, bool positive) -> double {
    const std::string& text = cells[header.fit_columns.at(name)];
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
  row.impactor.radius = cell("impactor_radius", true);
  row.impactor.density = cell("impactor_density", true);
  row.impactor.velocity = cell("velocity", true);
  row.target.density = cell("target_density", true);
  row.target.gravity = cell("gravity", false);
  row.target.strength = cell("strength", false);
  row.crater_radius = cell("crater_radius", true);
  if (header.fit_columns.contains(kSigmaColumn)) row.crater_radius_sigma = cell(kSigmaColumn, true);
  if (header.run) row.run = cells[*header.run];
  if (header.growth_ended) {
    const std::string& text = cells[*header.growth_ended];
    if (text != "true" && text != "false") {
      throw InputError(where + "column '" + kGrowthEndedColumn + "': '" + text +
                       "' is not allowed: must be true or false");
    }
    row.growth_ended = text == "true";
  }
  for (std::size_t position : header.group_positions) row.group_values.push_back(cells[position]);
  return row;
}

}  // namespace

RadiiTable parse_radii_csv(std::istream& in, const std::string& source_name, std::size_t expected_rows,
                           const RadiiReadCallback& progress) {
  RadiiTable table;
  table.source = source_name;
  table.rows.reserve(expected_rows);
  std::optional<detail::RadiiHeader> header;
  std::string line;
  std::vector<std::string> cells;
  RadiiReadProgress read;
  int line_number = 0;
  while (std::getline(in, line)) {
    read.bytes_read += line.size() + 1;
    ++line_number;
    // A UTF-8 byte-order mark (spreadsheet exports) is not part of the first column's name.
    if (line_number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
    const std::string content = trim(line);
    if (content.empty() || content.front() == '#') continue;
    split(content, cells);
    const std::string where = source_name + ":" + std::to_string(line_number) + ": ";
    if (!header) {
      header = detail::parse_radii_header(cells, where);
      table.group_columns = header->group_columns;
      continue;
    }
    if (cells.size() != header->column_count) {
      throw InputError(where + "row has " + std::to_string(cells.size()) + " cells but the header has " +
                       std::to_string(header->column_count) + " columns");
    }
    ImpactRecord row = parse_row(cells, *header, where);
    row.line = line_number;
    table.rows.push_back(std::move(row));
    if (progress && table.rows.size() % 65536 == 0) {
      read.rows = table.rows.size();
      progress(read);
    }
  }
  if (!header) throw InputError(source_name + ": empty file; a header row and data rows are required");
  if (table.rows.empty()) throw InputError(source_name + ": no data rows after the header");
  return table;
}

RadiiTable read_radii_csv(const std::filesystem::path& path, const RadiiReadCallback& progress) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open the radii table for reading");
  // Lines (an upper bound of the rows), counted in blocks: the rows' array is then allocated once.
  std::size_t lines = 0;
  std::vector<char> block(1 << 20);
  while (in) {
    in.read(block.data(), static_cast<std::streamsize>(block.size()));
    const auto got = static_cast<std::size_t>(in.gcount());
    lines += static_cast<std::size_t>(std::count(block.data(), block.data() + got, '\n'));
  }
  in.clear();
  in.seekg(0);
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  RadiiReadCallback with_total;
  if (progress) {
    with_total = [&](const RadiiReadProgress& p) {
      RadiiReadProgress q = p;
      q.bytes_total = ec ? 0 : size;
      progress(q);
    };
  }
  return parse_radii_csv(in, path.string(), lines + 1, with_total);
}

std::string format_radii_csv(const RadiiTable& table) {
  std::ostringstream out;
  out.precision(17);
  for (const auto& name : detail::required_radii_columns())
    out << name << (name == "crater_radius" ? "" : ",");
  if (table.has_sigma()) out << "," << kSigmaColumn;
  for (const auto& name : table.group_columns) out << "," << name;
  if (table.has_run()) out << "," << kRunColumn;
  if (table.has_growth_ended()) out << "," << kGrowthEndedColumn;
  out << "\n";
  for (const auto& row : table.rows) {
    out << row.impactor.radius << "," << row.impactor.density << "," << row.impactor.velocity << ","
        << row.target.density << "," << row.target.gravity << "," << row.target.strength << ","
        << row.crater_radius;
    if (table.has_sigma()) out << "," << row.crater_radius_sigma.value_or(0.0);
    for (const auto& value : row.group_values) out << "," << value;
    if (table.has_run()) out << "," << row.run.value_or("");
    if (table.has_growth_ended()) out << "," << (row.growth_ended.value_or(true) ? "true" : "false");
    out << "\n";
  }
  return out.str();
}

}  // namespace craterkit::scaling
