#pragma once
// The part every craterkit LAMMPS script shares (internal to dem/src): grains as `atom_style sphere` read
// from a data file, the contact law between grains and against the floor at z = 0, gravity along -z,
// velocity-Verlet with rotation, and the mean grain speed a run stops on (`fix halt`) once it is below the
// rest speed.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace craterkit::dem {

struct GranularScript {
  std::string title;     // the script's first line, a comment
  std::string boundary;  // LAMMPS `boundary` styles, e.g. "p p fm"
  std::string data_file;
  std::string contact_model;  // lammps_contact_model()
  std::string extra_fixes;    // more walls: whole lines, defined after the floor
  double gravity = 0;         // m/s^2
  double skin = 0;            // m, the neighbour list's skin
  double time_step = 0;       // s
  long check_every = 0;       // steps between rest checks (and thermo lines)
};

// At rest: the mean grain speed below `fraction` of sqrt(g d).
inline double rest_speed(double fraction, double gravity, double diameter) {
  return fraction * std::sqrt(gravity * diameter);
}

// Rest checks a thousand times over the longest run, at most every 100 steps.
inline long rest_check_interval(long max_steps) {
  return std::max(100L, max_steps / 1000);
}

// From the title to `thermo_style` (flushed, so that the log can be read while LAMMPS runs); defines
// v_mean_speed (m/s) for `fix halt`.
inline std::string granular_script_start(const GranularScript& s) {
  return fmt::format(R"(# {title}
units si
atom_style sphere
atom_modify map array
boundary {boundary}
newton off
comm_modify vel yes
read_data {data}
pair_style granular
pair_coeff * * {model}
fix floor all wall/gran granular {model} zplane 0.0 NULL
{extra}fix gravity all gravity {gravity:.17g} vector 0 0 -1
fix move all nve/sphere
neighbor {skin:.17g} bin
neigh_modify delay 0
timestep {dt:.17g}
variable speed atom sqrt(vx*vx+vy*vy+vz*vz)
compute mean_speed all reduce ave v_speed
variable mean_speed equal c_mean_speed
thermo {check}
thermo_style custom step atoms ke v_mean_speed
thermo_modify flush yes
)",
                     fmt::arg("title", s.title), fmt::arg("boundary", s.boundary),
                     fmt::arg("data", s.data_file), fmt::arg("model", s.contact_model),
                     fmt::arg("extra", s.extra_fixes), fmt::arg("gravity", s.gravity),
                     fmt::arg("skin", s.skin), fmt::arg("dt", s.time_step), fmt::arg("check", s.check_every));
}

}  // namespace craterkit::dem
