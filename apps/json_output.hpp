#pragma once
// Every JSON object the program prints or writes carries the version of craterkit that made it, under
// "craterkit_version" (first key), so that a result can be traced to the code.
#include <cmath>
#include <iostream>
#include <string>

#include <nlohmann/json.hpp>

#include "craterkit_version.hpp"

namespace craterkit::cli {

// A number, or null where it is not finite (JSON has no NaN or infinity).
inline nlohmann::json number_or_null(double x) {
  return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
}

// The object with "craterkit_version" added in front (an object already carrying it is left as it is).
template <class Json>
nlohmann::ordered_json with_version(const Json& object) {
  nlohmann::ordered_json out;
  out["craterkit_version"] = CRATERKIT_VERSION;
  for (const auto& [key, value] : object.items()) {
    if (key != "craterkit_version") out[key] = value;
  }
  return out;
}

// Prints the object (with the version) indented by two spaces, and a newline.
template <class Json>
void print_json(const Json& object) {
  std::cout << with_version(object).dump(2) << "\n";
}

}  // namespace craterkit::cli
