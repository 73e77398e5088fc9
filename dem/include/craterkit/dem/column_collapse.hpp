#pragma once
// The angle at which a granular pile stands: a column of grains against a back wall, released on a frictional
// floor, collapses and comes to rest; the flank of the deposit is measured as the SPH granular tests measure
// it (docs/validation.md, "Granular flow under gravity": the surface profile's least-squares line between 20
// % and 80 % of the pile's height on the falling side). docs/dem.md, "Angle of repose".
#include <cstdint>
#include <filesystem>
#include <vector>

#include "craterkit/common/flank_slope.hpp"
#include "craterkit/dem/grain_contact.hpp"
#include "craterkit/dem/grain_sizes.hpp"
#include "craterkit/dem/grains.hpp"

namespace craterkit::dem {

struct ColumnSpec {
  double width = 0.32;         // m, along x from the back wall at x = 0
  double height = 0.16;        // m
  double thickness = 0.06;     // m, periodic along y (a quasi-2D slab)
  double floor_length = 0.96;  // m, along x; a wall stands at its end
  GrainSizes grain_sizes{0.009, 0.011};
  double grain_density = 2500;  // kg/m^3
  GrainContact contact;
  double gravity = 9.81;  // m/s^2
  std::uint64_t seed = 1;
  double rest_speed_fraction = 1e-3;  // at rest: mean grain speed below this fraction of sqrt(g d_mean)
  // > 0: a quasi-static collapse, every grain's velocity and spin relaxed towards rest with this time (s), a
  // drag F = -m v / drag_time (LAMMPS `fix langevin` at zero temperature), as the SPH quasi-static pile does.
  double drag_time = 0;
  int processes = 1;
};

struct Deposit {
  Grains grains;
  SurfaceProfile profile;
  FlankFit flank;
  double collapse_time = 0;  // s of simulated time until the deposit was at rest
};

// Settles the column (a periodic bed of the column's width), puts it against the back wall and lets it
// collapse until it rests. Runs LAMMPS in `folder`.
[[nodiscard]] Deposit collapse_column(const ColumnSpec& spec, const std::filesystem::path& folder);

// The surface profile over 0 <= x < length in columns `cell` wide.
[[nodiscard]] SurfaceProfile surface_profile(const Grains& grains, double length, double cell);

}  // namespace craterkit::dem
