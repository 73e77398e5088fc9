#include "craterkit/chronology/scaled_production.hpp"

namespace craterkit::chronology {

ImpactorRadiusFunction scaled_impactor_radius(const scaling::ScalingLaw& law, const scaling::Target& target,
                                              double impactor_density) {
  scaling::validate(law);
  return [law, target, impactor_density](double apparent_radius, double speed) {
    scaling::Impactor impactor;
    impactor.density = impactor_density;
    impactor.velocity = speed;
    return scaling::solve_impactor_radius(law, apparent_radius, impactor, target);
  };
}

}  // namespace craterkit::chronology
