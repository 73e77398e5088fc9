#pragma once
// Checks of single numbers (a function's arguments, a set-up's fields, a value read from a file) with one
// wording for every failure: craterkit::InputError "<what>: value <v> out of range: allowed <range>", the
// range written as an interval ("(0, inf)", "[0, 1]"). The TOML reader (toml_table.hpp) reports its
// ranges in the same words, so a value is described alike wherever it is checked.
#include <string>
#include <string_view>

namespace craterkit {

// The interval from lo to hi as text: "(" or ")" for an open end, "[" or "]" for a closed one; an
// infinite end is always open, since infinite values are never allowed.
std::string range_text(double lo, double hi, bool lo_open = false, bool hi_open = false);

// "value <v> out of range: allowed <allowed>", the text of every range error.
std::string out_of_range_text(double value, std::string_view allowed);

// Whether value is finite and inside the interval.
bool in_range(double value, double lo, double hi, bool lo_open = false, bool hi_open = false);

// A finite value inside the interval, else InputError "<what>: value <v> out of range: allowed <range>".
void require_in_range(double value, std::string_view what, double lo, double hi, bool lo_open = false,
                      bool hi_open = false);
// A finite value > 0.
void require_positive(double value, std::string_view what);
// A finite value >= 0.
void require_non_negative(double value, std::string_view what);

}  // namespace craterkit
