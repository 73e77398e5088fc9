#pragma once
// The crater of a set of grains, measured as the crater of an SPH run (docs/crater_measurement.md): each
// grain becomes a particle of its mass standing for the volume it takes in the bulk, V = m / rho_bulk, with
// the SPH set-up's smoothing length h = eta V^(1/3), and the same measurement (the iso-surface at half the
// initial bulk density, the rim search inward from the crest, quarter-domain mirror images) runs on them.
// Flying grains count as ejected, frozen grains as the fixed shell.
#include <vector>

#include "craterkit/dem/grains.hpp"
#include "craterkit/impact/crater_measurement.hpp"
#include "craterkit/sph/particles/particles.hpp"

namespace craterkit::dem_late_stage {

struct GrainMeasurement {
  double bulk_density = 0.0;  // kg/m^3 of the undisturbed bed
  double eta = 1.2;           // h = eta (m / rho_bulk)^(1/3), the SPH set-up's
  // The height of the grains' surface far from the crater at the hand-off: the crater is measured at this
  // level, the pre-impact plane of the grains (docs/dem.md, "Crater on the grains").
  double plane_height = 0.0;  // m
};

// The grains as particles (z shifted by -plane_height). roles: GrainRole per grain (empty: all moving).
[[nodiscard]] sph::Particles grains_as_particles(const dem::Grains& grains, const std::vector<int>& roles,
                                                 const GrainMeasurement& measurement);

// The mean height of the grains' iso-surface (rho_bulk / 2) over the columns at (x, y), NaN-free columns
// only; InputError when no column has a surface.
[[nodiscard]] double grain_surface_height(const dem::Grains& grains, const std::vector<int>& roles,
                                          double bulk_density, double eta,
                                          const std::vector<std::array<double, 2>>& columns);

}  // namespace craterkit::dem_late_stage
