#pragma once
// The name of a run, and of its folder DIR/runs/<name>: its axis values in study order as
// "<key>-<value>" joined by '_' (projectile_mass-0.05_cohesion-0.2), numbers in their shortest exact form,
// every character other than letters, digits and . , + - replaced by '_'; "base" for a run without axis
// values. Names longer than 120 characters are cut and end in a hash of the whole name.
#include <string>
#include <vector>

#include "craterkit/study/study_file.hpp"

namespace craterkit::study {

std::string value_slug(const AxisValue& value);
std::string run_name(const std::vector<AxisValue>& values);

}  // namespace craterkit::study
