#pragma once
// The report's chronology under a fitted law (report.hpp), as `craterkit rates` and `craterkit age` compute
// it with their defaults for Ryugu (main-belt population and collision environment, impactor density
// 2600 kg/m^3, rim diameter 1.2 apparent diameters; docs/chronology.md).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "craterkit/scaling/point_source.hpp"

namespace craterkit::cli {

// The cohesion (Pa) the rates are relative to.
inline constexpr double kReferenceCohesion = 1.0;

// Crater-formation rates on Ryugu per cohesion against crater diameter (rim-to-rim, 10 to 300 m), relative
// to kReferenceCohesion: JSON (body, population, speed, conventions, rows {cohesion, crater_diameter,
// production_rate_per_km2_per_yr, relative_rate}) and a Markdown table of a few diameters.
nlohmann::json ryugu_rates(const scaling::ScalingLaw& law, const std::vector<double>& cohesions,
                           std::string& markdown);

// Model ages per cohesion of the real Ryugu counts shipped (data/craters/README.md): N(>=20 m) = 77, and
// its split into the 66 craters of 20-100 m and the 11 of >= 100 m. Each age with its median, mode, 1- and
// 2-sigma ranges and its probability density (thinned to every tenth point of its grid).
nlohmann::json ryugu_ages(const scaling::ScalingLaw& law, const std::vector<double>& cohesions,
                          std::string& markdown);

}  // namespace craterkit::cli
