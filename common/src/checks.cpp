#include "craterkit/common/checks.hpp"

#include <cmath>
#include <limits>

#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"

namespace craterkit {

std::string range_text(double lo, double hi, bool lo_open, bool hi_open) {
  return std::string(lo_open || std::isinf(lo) ? "(" : "[") + format_number(lo) + ", " + format_number(hi) +
         (hi_open || std::isinf(hi) ? ")" : "]");
}

std::string out_of_range_text(double value, std::string_view allowed) {
  return "value " + format_number(value) + " out of range: allowed " + std::string(allowed);
}

bool in_range(double value, double lo, double hi, bool lo_open, bool hi_open) {
  const bool above_lo = lo_open ? value > lo : value >= lo;
  const bool below_hi = hi_open ? value < hi : value <= hi;
  return std::isfinite(value) && above_lo && below_hi;
}

void require_in_range(double value, std::string_view what, double lo, double hi, bool lo_open, bool hi_open) {
  if (!in_range(value, lo, hi, lo_open, hi_open)) {
    throw InputError(std::string(what) + ": " +
                     out_of_range_text(value, range_text(lo, hi, lo_open, hi_open)));
  }
}

void require_positive(double value, std::string_view what) {
  require_in_range(value, what, 0.0, std::numeric_limits<double>::infinity(), true);
}

void require_non_negative(double value, std::string_view what) {
  require_in_range(value, what, 0.0, std::numeric_limits<double>::infinity());
}

}  // namespace craterkit
