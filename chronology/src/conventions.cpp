#include "craterkit/chronology/conventions.hpp"

#include <cmath>

#include "craterkit/common/input_error.hpp"

namespace craterkit::chronology {

void validate(const DiameterConvention& c, const std::string& what) {
  if (!(c.rim_to_apparent >= 1.0 && c.rim_to_apparent <= 2.0)) {
    throw InputError(what + " = " + std::to_string(c.rim_to_apparent) +
                     " is outside the allowed range [1, 2] (rim-to-rim over apparent diameter)");
  }
}

std::string to_string(CollisionRegion region) {
  return region == CollisionRegion::main_belt ? "main_belt" : "near_earth";
}

CollisionRegion collision_region_from_string(const std::string& text) {
  if (text == "main_belt" || text == "main-belt") return CollisionRegion::main_belt;
  if (text == "near_earth" || text == "near-earth") return CollisionRegion::near_earth;
  throw InputError("collision region '" + text + "' is not known; allowed: main_belt, near_earth");
}

void validate(const EquilibriumCap& cap) {
  if (cap.enabled && !(cap.fraction_of_geometric > 0.0 && cap.fraction_of_geometric <= 1.0)) {
    throw InputError("equilibrium fraction = " + std::to_string(cap.fraction_of_geometric) +
                     " is outside the allowed range (0, 1] (fraction of the geometric saturation 1.54 D^-2)");
  }
}

double equilibrium_density(const EquilibriumCap& cap, double rim_diameter) {
  return cap.fraction_of_geometric * geometric_saturation_coefficient / (rim_diameter * rim_diameter);
}

double expected_cumulative_density(const EquilibriumCap& cap, double rim_diameter, double age_years,
                                   double production_rate) {
  const double linear = age_years * production_rate;
  if (!cap.enabled) return linear;
  const double n_eq = equilibrium_density(cap, rim_diameter);
  return -n_eq * std::expm1(-linear / n_eq);
}

}  // namespace craterkit::chronology
