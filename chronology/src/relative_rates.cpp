#include "craterkit/chronology/relative_rates.hpp"

namespace craterkit::chronology {

RelativeRate relative_rate(const ProductionSetup& setup, const ImpactorRadiusFunction& law_a,
                           const ImpactorRadiusFunction& law_b, double rim_diameter) {
  validate(setup.speeds);
  RelativeRate out;
  out.rim_diameter = rim_diameter;
  const double R = apparent_radius_from_rim_diameter(rim_diameter, setup.diameter);
  out.impactor_radius_a = law_a(R, setup.speeds.speed.front());
  out.impactor_radius_b = law_b(R, setup.speeds.speed.front());
  out.rate_a = crater_production_rate(setup, law_a, rim_diameter);
  out.rate_b = crater_production_rate(setup, law_b, rim_diameter);
  out.ratio = out.rate_b / out.rate_a;
  return out;
}

}  // namespace craterkit::chronology
