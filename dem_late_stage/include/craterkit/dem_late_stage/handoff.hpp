#pragma once
// The hand-off from the SPH shock stage to a granular DEM late stage (docs/dem.md, "Hand-off"): a settled bed
// of grains in the impact's coordinates (the pre-impact plane at z = 0, mirror planes x = 0 and y = 0 of a
// quarter-domain run) is cut to the shape the SPH material has at the hand-off time and set moving as the SPH
// material moves there.
//   1. The SPH particles split into those already ejected (they left the SPH run: not handed over), fast
//      ejecta (faster than `ejecta_speed`, rising, above z = 0: each becomes one grain of its own mass in
//      free flight) and the rest, the material that takes part in the flow.
//   2. Carving: a bed grain is kept where the interpolated, unnormalised density of that material,
//      rho(x) = sum_j m_j W(|x - x_j|, h_j), reaches `critical_density` at its centre: the iso-surface that
//      the crater measurement takes as the free surface (docs/crater_measurement.md), here the surface
//      between the compact material and the ejecta. Beyond the SPH domain (|x| > R_dom - 2 h_max) a grain
//      below z = 0 is kept as undisturbed ground.
//   3. Motion: each kept grain takes the mass-weighted mean velocity of the SPH particles near it,
//      v_g = sum_j w_j v_j / sum_j w_j with w_j = m_j W(|x_g - x_j|, max(h_j, d_g / 2)) (a kernel at least a
//      grain wide, so that a grain between coarse particles still sees them), and the spin of the local
//      flow, omega_g = curl(v) / 2, from a weighted least-squares fit of the velocity gradient about the
//      neighbours' weighted centroid (exact for a linear field; zero where the neighbours do not span three
//      dimensions). Grains without SPH neighbours rest.
//   4. Grains within `frozen_thickness` of the bed's bottom or of its outer sides x = L_x, y = L_y are
//   frozen:
//      they hold the bed as the SPH run's fixed shell holds the target.
// Mass, momentum and kinetic energy of each part before and after are returned (HandoffBalance); what the
// grains do not carry of the SPH material's momentum and energy is reported there, not corrected.
#include <array>
#include <cstddef>
#include <vector>

#include "craterkit/dem/grains.hpp"
#include "craterkit/dem/lammps_files.hpp"
#include "craterkit/sph/particles/kernel.hpp"
#include "craterkit/sph/particles/particles.hpp"

namespace craterkit::dem_late_stage {

// A grain's part in the late stage; the value is its LAMMPS atom type.
enum class GrainRole : int {
  moving = 1,  // a grain of the bed, integrated, in contact with everything but flying grains
  frozen = 2,  // the bed's outer shell: contacts, no motion
  flying = 3,  // fast ejecta: ballistic, no contacts, lost when they leave the box
};

struct HandoffSpec {
  dem::Box bed_box;                   // m: x in [0, L_x], y in [0, L_y], z from the bed's bottom to its top
  double frozen_thickness = 0.0;      // m, > 0
  double critical_density = 0.0;      // kg/m^3, > 0: half the target's initial bulk density
  double ejecta_speed = 0.0;          // m/s, > 0
  double flying_grain_density = 0.0;  // kg/m^3, > 0: sets a flying grain's diameter from its mass
  double sph_domain_radius = 0.0;     // m; 0: the SPH material covers the whole bed
  sph::KernelType kernel = sph::KernelType::cubic_spline;
  bool quarter_symmetric = true;  // the SPH particles fill x >= 0, y >= 0 with mirror planes there
};

// Mass (kg), momentum (kg m/s) and kinetic energy (J; translational plus rotational for grains) of a set.
struct MotionTotals {
  std::size_t count = 0;
  double mass = 0.0;
  std::array<double, 3> momentum{0.0, 0.0, 0.0};
  double kinetic_energy = 0.0;
};

struct HandoffBalance {
  MotionTotals sph_ejected;      // left the SPH run before the hand-off: not handed over
  MotionTotals sph_flying;       // fast ejecta, handed over one to one as flying grains
  MotionTotals sph_in_bed;       // the flowing material inside the bed's box
  MotionTotals sph_outside_bed;  // the flowing material outside it: not handed over
  MotionTotals grains_moving, grains_frozen, grains_flying;
  double grains_rotational_energy = 0.0;      // J, part of the grains' kinetic energies
  std::size_t grains_carved = 0;              // bed grains removed by the carving
  std::size_t grains_without_neighbours = 0;  // kept grains with no SPH particle near them (at rest)
  double max_moving_speed = 0.0;              // m/s, the fastest moving grain
};

struct Handoff {
  dem::Grains grains;
  std::vector<int> roles;  // GrainRole per grain, as int (the LAMMPS atom type)
  HandoffBalance balance;
};

// InputError naming the field when a value of the spec is out of range.
void check_handoff_spec(const HandoffSpec& spec);

// The grains of the late stage from the SPH particles at the hand-off and a settled bed given in the
// impact's coordinates (grains at rest, inside spec.bed_box).
[[nodiscard]] Handoff hand_off(const sph::Particles& sph, const dem::Grains& bed, const HandoffSpec& spec);

[[nodiscard]] MotionTotals grain_totals(const dem::Grains& grains, const std::vector<int>& roles,
                                        GrainRole role);

}  // namespace craterkit::dem_late_stage
