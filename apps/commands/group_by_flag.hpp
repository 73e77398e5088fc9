#pragma once
// --group-by of the commands that fit a radii table per group (`craterkit fit`, `craterkit report`):
// "none" (one fit over every row) or grouping column names, comma-separated.
#include <algorithm>
#include <string>
#include <vector>

#include "craterkit/common/input_error.hpp"

namespace craterkit::cli {

inline std::vector<std::string> parse_group_by(const std::string& text) {
  if (text == "none") return {};
  std::vector<std::string> names;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string name = text.substr(start, comma - start);
    if (name.empty() || name == "none") {
      throw InputError("--group-by '" + text +
                       "' is not allowed: use none, or grouping column names separated by commas");
    }
    names.push_back(name);
    start = comma + 1;
  }
  return names;
}

}  // namespace craterkit::cli
