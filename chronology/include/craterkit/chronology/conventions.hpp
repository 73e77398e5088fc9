#pragma once
// Conventions of crater chronology that published work handles in different ways (docs/physics.md sec. 7).
// Each is explicit here and configurable, with the default stated once.
#include <string>

namespace craterkit::chronology {

// Scaling laws give the apparent radius at the pre-impact level; counts are rim-to-rim diameters,
// about 1.2-1.3 times the apparent diameter (SCI: 14.5 m apparent, about 17.6 m rim-to-rim, i.e. 1.21).
struct DiameterConvention {
  double rim_to_apparent = 1.2;  // D_rim / D_apparent, allowed [1, 2]
};

inline double rim_diameter_from_apparent_radius(double apparent_radius, const DiameterConvention& c) {
  return 2.0 * apparent_radius * c.rim_to_apparent;
}
inline double apparent_radius_from_rim_diameter(double rim_diameter, const DiameterConvention& c) {
  return rim_diameter / (2.0 * c.rim_to_apparent);
}

// Throws InputError naming `what` (e.g. "rim_to_apparent") unless 1 <= rim_to_apparent <= 2.
void validate(const DiameterConvention& c, const std::string& what = "rim_to_apparent");

// Which impactor environment the collision probability and speed describe. Ryugu and Bennu are
// near-Earth asteroids now, but most of their large craters formed in the main belt, where the
// intrinsic collision probability is far higher (Bottke et al. 1994).
enum class CollisionRegion { main_belt, near_earth };
std::string to_string(CollisionRegion region);                          // "main_belt" | "near_earth"
CollisionRegion collision_region_from_string(const std::string& text);  // InputError if unknown

// Impact cross-section of a target of radius R_t and an impactor of radius a. Bottke et al. (1994)
// define the intrinsic collision probability P_i per unit (R_t + a)^2; for a << R_t the impactor's
// own radius is often dropped (target_only). Rate of impacts by impactors larger than a:
//   dN_imp/dt = P_i (R_t + a)^2 N(>a)   or   P_i R_t^2 N(>a).
enum class CrossSection { target_plus_impactor, target_only };

// Optional equilibrium (saturation) cap on the cumulative crater density. The geometric saturation of
// Gault (1970) is N_geo(>D) = 1.54 D^-2 (per unit area, D in the same length unit); observed
// equilibrium densities are a few per cent to about ten per cent of it (Melosh 1989, ch. 10), so the
// fraction is the user's choice. With the cap, the expected density approaches equilibrium smoothly:
//   N(>D, t) = N_eq(D) [1 - exp(-t r(D) / N_eq(D))],   N_eq(D) = fraction * 1.54 D^-2,
// which equals t r(D) while t r(D) << N_eq (r the production rate per unit area and time).
struct EquilibriumCap {
  bool enabled = false;
  double fraction_of_geometric = 0.05;  // allowed (0, 1]
};
inline constexpr double geometric_saturation_coefficient = 1.54;  // Gault (1970)

double equilibrium_density(const EquilibriumCap& cap, double rim_diameter);  // N_eq(>D), per m^2
void validate(const EquilibriumCap& cap);

// Expected cumulative crater density N(>D) per m^2 after time t (years) for production rate r (per m^2
// per year) with or without the cap.
double expected_cumulative_density(const EquilibriumCap& cap, double rim_diameter, double age_years,
                                   double production_rate);

}  // namespace craterkit::chronology
