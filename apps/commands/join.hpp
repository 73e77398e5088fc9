#pragma once
// Items joined into one line of text: "a, b, c".
#include <string>
#include <vector>

namespace craterkit::cli {

inline std::string join(const std::vector<std::string>& items, const std::string& separator = ", ") {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : separator) + item;
  return out;
}

}  // namespace craterkit::cli
