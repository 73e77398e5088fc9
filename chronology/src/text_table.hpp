#pragma once
// Private helpers for the small text tables chronology reads (CSV, craterstats .diam/.scc): numbers
// parsed strictly, every error naming file, line and column.
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "craterkit/common/input_error.hpp"

namespace craterkit::chronology::detail {

inline std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return s.substr(first, last - first + 1);
}

inline std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Splits on commas if the line has any, otherwise on whitespace (tabs or spaces).
inline std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> out;
  if (line.find(',') != std::string::npos) {
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) out.push_back(trim(cell));
  } else {
    std::stringstream ss(line);
    std::string cell;
    while (ss >> cell) out.push_back(cell);
  }
  return out;
}

inline std::vector<std::string> read_lines(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open file for reading");
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    // A UTF-8 byte-order mark (spreadsheet exports) is not part of the first line.
    if (lines.empty() && line.rfind("\xEF\xBB\xBF", 0) == 0) line.erase(0, 3);
    lines.push_back(line);
  }
  return lines;
}

// Location string "file:line" (1-based line).
inline std::string where(const std::string& path, std::size_t line_index) {
  return path + ":" + std::to_string(line_index + 1);
}

// Parses a finite number; throws naming file:line, column and value.
inline double parse_number(const std::string& text, const std::string& path, std::size_t line_index,
                           const std::string& column) {
  const std::string t = trim(text);
  double value = 0.0;
  const auto* begin = t.data();
  const auto* end = t.data() + t.size();
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (t.empty() || ec != std::errc() || ptr != end || !std::isfinite(value)) {
    throw InputError(where(path, line_index) + ": column '" + column + "': '" + t +
                     "' is not a finite number");
  }
  return value;
}

}  // namespace craterkit::chronology::detail
