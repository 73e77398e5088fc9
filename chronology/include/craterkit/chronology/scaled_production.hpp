#pragma once
// The link between chronology and the point-source scaling law (docs/physics.md sec. 6): the inverse law
// a(R; Y, U) as an ImpactorRadiusFunction for crater production and relative rates.
#include "craterkit/chronology/production.hpp"
#include "craterkit/scaling/point_source.hpp"

namespace craterkit::chronology {

// a(R, U) = scaling::solve_impactor_radius(law, R, {density = impactor_density, velocity = U}, target),
// with target.strength the cohesion Y (Pa) of the scaling law.
ImpactorRadiusFunction scaled_impactor_radius(const scaling::ScalingLaw& law, const scaling::Target& target,
                                              double impactor_density);

}  // namespace craterkit::chronology
