// The crater measured on grains (dem_late_stage/grain_crater.hpp): a bed of grains with a bowl cut out of it
// measures as the bowl, at the level of the grains' own flat surface.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "craterkit/dem_late_stage/grain_crater.hpp"
#include "craterkit/dem_late_stage/handoff.hpp"

namespace craterkit::dem_late_stage {
namespace {

constexpr double spacing = 0.3;                                      // m, cubic lattice
constexpr double grain_density = 2200.0;                             // kg/m^3
const double bulk_density = grain_density * std::numbers::pi / 6.0;  // touching spheres
constexpr double top = -0.15;                                        // m, top layer's centres

// A quarter bed x, y in [0, 8] m, from z = -4 m to the top layer at z = -0.15 m, without the grains whose
// centres lie inside a sphere of radius `bowl` about (0, 0, bowl_centre), and a rim: one more layer on top
// from the bowl's edge out to `rim` m beyond it.
dem::Grains bed_with_bowl(double bowl, double bowl_centre, double rim = 0.0) {
  dem::Grains grains;
  const double edge = bowl > 0.0 ? std::sqrt(bowl * bowl - (top - bowl_centre) * (top - bowl_centre)) : 0.0;
  for (double x = 0.5 * spacing; x < 8.0; x += spacing)
    for (double y = 0.5 * spacing; y < 8.0; y += spacing) {
      const double r = std::hypot(x, y);
      if (r > edge && r < edge + rim) grains.add(x, y, top + spacing, spacing, grain_density);
    }
  for (double x = 0.5 * spacing; x < 8.0; x += spacing)
    for (double y = 0.5 * spacing; y < 8.0; y += spacing)
      for (double z = top; z > -4.0; z -= spacing) {
        const double dz = z - bowl_centre;
        if (x * x + y * y + dz * dz < bowl * bowl) continue;
        grains.add(x, y, z, spacing, grain_density);
      }
  return grains;
}

TEST(GrainCrater, TheFlatSurfaceOfALatticeLiesHalfASpacingAboveItsTopLayer) {
  const auto grains = bed_with_bowl(0.0, 0.0);
  const double surface =
      grain_surface_height(grains, {}, bulk_density, 1.2, {{4.05, 4.05}, {5.25, 3.15}, {6.15, 6.15}});
  // An SPH lattice's half-density surface sits about half a spacing above its top layer.
  EXPECT_NEAR(surface, top + 0.5 * spacing, 0.1 * spacing);
}

TEST(GrainCrater, ABowlCutIntoTheGrainsMeasuresAsTheBowl) {
  // A spherical cap: centre 2 m above the plane, radius 3.5 m: it meets the plane at sqrt(3.5^2 - 2^2) m.
  const double bowl = 3.5, centre = 2.0;
  const double radius_at_plane = std::sqrt(bowl * bowl - centre * centre);
  const auto grains = bed_with_bowl(bowl, centre, 1.5);
  const double plane =
      grain_surface_height(grains, {}, bulk_density, 1.2, {{6.5, 6.5}, {7.0, 6.0}, {6.0, 7.0}});
  const auto particles = grains_as_particles(grains, {}, {bulk_density, 1.2, plane});
  impact::CraterMeasurementOptions options;
  options.rho_initial = bulk_density;
  options.particle_spacing = spacing;
  options.quarter_symmetric = true;
  options.max_radius = 7.0;
  const auto m = impact::measure_crater(particles, options);
  // The grains' surface follows the bowl about half a spacing inside it (as at the flat top): the measured
  // edge lies where that surface meets the plane, within a spacing of the cut. (Without a rim the plane
  // density outside the edge only approaches the critical density, and the edge is ill-conditioned:
  // docs/crater_measurement.md.)
  EXPECT_NEAR(m.crater_radius, radius_at_plane, spacing) << m.crater_radius;
  EXPECT_NEAR(m.depth, bowl - centre, spacing) << m.depth;
  EXPECT_EQ(m.ejected_mass, 0.0);
}

TEST(GrainCrater, FlyingGrainsAreEjectaAndFrozenGrainsTheShell) {
  dem::Grains grains;
  grains.add(1.0, 1.0, 1.0, 0.3, grain_density);
  grains.add(1.0, 1.0, -1.0, 0.3, grain_density);
  grains.add(1.0, 1.0, -2.0, 0.3, grain_density);
  const std::vector<int> roles{static_cast<int>(GrainRole::flying), static_cast<int>(GrainRole::moving),
                               static_cast<int>(GrainRole::frozen)};
  const auto p = grains_as_particles(grains, roles, {bulk_density, 1.2, 0.5});
  EXPECT_EQ(p.flags[0], sph::particle_ejected);
  EXPECT_EQ(p.flags[1], 0);
  EXPECT_EQ(p.flags[2], sph::particle_fixed);
  EXPECT_DOUBLE_EQ(p.z[1], -1.5);
  EXPECT_DOUBLE_EQ(p.mass[0], grains.mass(0));
  EXPECT_NEAR(p.smoothing_length[1], 1.2 * std::cbrt(grains.mass(1) / bulk_density), 1e-15);
}

}  // namespace
}  // namespace craterkit::dem_late_stage
