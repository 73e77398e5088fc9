#pragma once
// Numbers in messages (errors, reports): shortest readable form with enough digits to tell values apart.
#include <sstream>
#include <string>

namespace craterkit {

inline std::string format_number(double value, int significant_digits = 10) {
  std::ostringstream out;
  out.precision(significant_digits);
  out << value;
  return out.str();
}

}  // namespace craterkit
