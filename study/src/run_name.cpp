#include "craterkit/study/run_name.hpp"

#include <charconv>
#include <cstdint>

#include <fmt/format.h>

namespace craterkit::study {

namespace {

bool allowed(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '.' || c == ',' ||
         c == '+' || c == '-';
}

std::string sanitise(const std::string& text) {
  std::string out;
  for (const char c : text) out += allowed(c) ? c : '_';
  return out;
}

std::string shortest(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 1469598103934665603ull;
  for (const char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace

std::string value_slug(const AxisValue& value) {
  if (value.number) return shortest(*value.number);
  // Strings without their quotes, arrays without brackets and the blanks after commas: "quarter",
  // "0.0,0.0,-1.0".
  const std::string& text = value.literal;
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '"' || c == '\'' || c == '[' || c == ']' || c == '{' || c == '}') continue;
    if (c == ' ' && i > 0 && text[i - 1] == ',') continue;
    out += c;
  }
  return out.empty() ? "empty" : out;
}

std::string run_name(const std::vector<AxisValue>& values) {
  if (values.empty()) return "base";
  std::string name;
  for (const auto& v : values) name += (name.empty() ? "" : "_") + v.key + "-" + value_slug(v);
  name = sanitise(name);
  if (name.size() > 120) name = name.substr(0, 103) + "-" + fmt::format("{:016x}", fnv1a(name));
  return name;
}

}  // namespace craterkit::study
