#pragma once
// The [impact] table of a `craterkit simulate` configuration (problem.setup = "impact"; keys, defaults and
// ranges in docs/impact_setup.md), with its [[impact.boulders]] array. Same rules as config.hpp: unknown
// keys, wrong types and out-of-range values are craterkit::InputError "<source>: impact.<key>: ..." (a
// boulder's keys as impact.boulders[<i>].<key>, its parts as impact.boulders[<i>].parts[<j>].<key>).
#include <string>

#include <toml++/toml.h>

#include "craterkit/impact/impact_setup.hpp"

namespace craterkit::sph {

ImpactSetup parse_impact_setup(const toml::table& impact, const std::string& source);

}  // namespace craterkit::sph
