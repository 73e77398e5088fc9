#include <string>

#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/point_source.hpp"

namespace craterkit::scaling {

std::string to_string(Form form) {
  return form == Form::holsapple ? "holsapple" : "hh2011";
}

Form form_from_string(const std::string& text) {
  if (text == "holsapple") return Form::holsapple;
  if (text == "hh2011") return Form::hh2011;
  throw InputError("scaling form '" + text + "' is not known; allowed: holsapple, hh2011");
}

std::string coefficient_name(Form form, int which) {
  if (form == Form::holsapple) return which == 1 ? "K1" : "K2";
  return which == 1 ? "H1" : "H2";
}

}  // namespace craterkit::scaling
