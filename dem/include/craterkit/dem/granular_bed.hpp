#pragma once
// A bed of grains settled under gravity: grains dropped from a loose lattice into a box periodic in x and y
// (or between frictionless side walls) on a frictional floor at z = 0, settled until they rest, cut flat at
// the bed's depth and settled again. Settling costs minutes for a large bed, so a bed is cached under a hash
// of everything that defines it (docs/dem.md, "Settled bed").
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "craterkit/dem/grain_contact.hpp"
#include "craterkit/dem/grain_sizes.hpp"
#include "craterkit/dem/grains.hpp"
#include "craterkit/dem/lammps_files.hpp"

namespace craterkit::dem {

struct BedSpec {
  double length_x = 0.2;  // m
  double length_y = 0.2;  // m
  // false: periodic in x and y; true: frictionless walls at x = 0, length_x and y = 0, length_y (a bed for a
  // box whose sides x = 0 and y = 0 are mirror planes, as the late stage of a quarter-domain impact).
  bool side_walls = false;
  double depth = 0.1;  // m, the flat surface after the cut
  GrainSizes grain_sizes;
  double grain_density = 2500;  // kg/m^3 of the grain material
  GrainContact contact;
  double gravity = 9.81;  // m/s^2, along -z
  std::uint64_t seed = 1;
  // At rest: the grains' mean speed below this fraction of sqrt(g d_mean).
  double rest_speed_fraction = 1e-3;
  int processes = 1;  // LAMMPS processes (mpirun); does not change the cache key
};

// InputError naming the key for a value out of range.
void check_bed_spec(const BedSpec& spec);

struct SettledBed {
  Grains grains;
  Box box;                    // x, y (periodic or walled); z from the floor up
  double surface_height = 0;  // m: the mean top of the surface grains (docs/dem.md)
  // Grain volume over bed volume in the bulk: from 2 d_max above the floor to 2 d_max below the surface (the
  // layers at a wall pack looser).
  double packing_fraction = 0;
  double bulk_density = 0;  // packing_fraction x grain density
};

// A stable text that defines the bed (every field but `processes`) and its 64-bit FNV-1a hash.
[[nodiscard]] std::string bed_key(const BedSpec& spec);
[[nodiscard]] std::string bed_hash(const BedSpec& spec);

// A line of progress (may be empty: none).
using ProgressLine = std::function<void(const std::string&)>;

// Settles the bed with LAMMPS in `folder` (created; holds the script, log and files); progress every 30 s
// from LAMMPS's log (step, mean grain speed against the rest speed).
[[nodiscard]] SettledBed settle_bed(const BedSpec& spec, const std::filesystem::path& folder,
                                    const ProgressLine& progress = {});

// The bed from `cache/bed-<hash>.dump` when present, else settled in `cache/bed-<hash>/` and stored there
// (atomically, with its key beside it in bed-<hash>.key).
[[nodiscard]] SettledBed settled_bed_cached(const BedSpec& spec, const std::filesystem::path& cache,
                                            const ProgressLine& progress = {});

// The fraction of the box's slab low <= z <= high filled by grain volume (spheres cut by the planes).
[[nodiscard]] double packing_fraction_between(const Grains& grains, const Box& box, double low, double high);

// The elastic energy stored in the overlaps of the grains' contacts with this contact law (Hertz, summed over
// every overlapping pair; walls not counted), J.
[[nodiscard]] double contact_elastic_energy(const Grains& grains, const GrainContact& contact);

// The mean height of the surface: the box's floor cut into square columns `cell` wide, in each the highest
// grain top (z + d/2), averaged over the columns that hold a grain.
[[nodiscard]] double mean_surface_height(const Grains& grains, const Box& box, double cell);

}  // namespace craterkit::dem
