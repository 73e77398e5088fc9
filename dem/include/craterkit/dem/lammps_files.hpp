#pragma once
// The files craterkit and LAMMPS exchange: a data file of `atom_style sphere` grains (with velocities and
// angular velocities) that LAMMPS reads, and the `custom` dump of the grains that it writes back.
#include <filesystem>
#include <span>
#include <vector>

#include "craterkit/dem/grains.hpp"

namespace craterkit::dem {

struct Box {
  double x_low = 0, x_high = 0, y_low = 0, y_high = 0, z_low = 0, z_high = 0;
};

// Writes the grains as a LAMMPS data file (atom ids 1..N in order), atomically. types: each grain's atom type
// (1, 2, ...; a script tells them apart by it); empty: all of type 1.
void write_lammps_data(const std::filesystem::path& path, const Grains& grains, const Box& box,
                       std::span<const int> types = {});

// Reads a dump written with `write_dump all custom FILE id diameter mass x y z vx vy vz omegax omegay omegaz
// modify sort id`: the grains in id order, their density from mass and diameter. std::runtime_error naming
// the file and line when it is not such a dump. ids: when given, receives each grain's atom id (grains that
// left a box with fixed sides are missing from a dump).
[[nodiscard]] Grains read_lammps_dump(const std::filesystem::path& path, std::vector<long>* ids = nullptr);

// The columns read_lammps_dump expects, for the write_dump command.
inline constexpr const char* dump_columns = "id diameter mass x y z vx vy vz omegax omegay omegaz";

}  // namespace craterkit::dem
