#pragma once
// Conventions that turn scaling-law radii into the diameters crater counts measure (physics.md sec. 7).
namespace craterkit::chronology {

// Scaling laws give the apparent radius at the pre-impact level; counts are rim-to-rim diameters,
// about 1.2-1.3 times the apparent diameter (SCI: 14.5 m apparent, about 17.6 m rim-to-rim).
struct DiameterConvention {
  double rim_to_apparent = 1.2;  // D_rim / D_apparent
};

inline double rim_diameter_from_apparent_radius(double apparent_radius, const DiameterConvention& c) {
  return 2.0 * apparent_radius * c.rim_to_apparent;
}
inline double apparent_radius_from_rim_diameter(double rim_diameter, const DiameterConvention& c) {
  return rim_diameter / (2.0 * c.rim_to_apparent);
}

}  // namespace craterkit::chronology
