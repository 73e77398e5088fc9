#pragma once
// Crater measurement on a particle set (docs/physics.md section 5).
//
// The continuum density is interpolated with the SPH kernel WITHOUT normalisation,
//   rho(x) = sum_j m_j W(|x - x_j|, h_j)      (ejected particles excluded),
// so that a flat undisturbed free surface reads rho_initial/2 on the surface itself: the iso-surface
// rho = rho_crit = rho_initial/2 is the free surface. Everything below is measured on that iso-surface.
//
// Sampling: a polar grid centred on the impact point, n_azimuths rays (a multiple of 4, so that
// +x, +y, -x, -y are rays 0, n/4, n/2, 3n/4) and radii r_k = (k + 1/2) dr up to max_radius. On every
// sample column (x, y) the code finds
//   * the surface height z_s(x, y): the HIGHEST z where rho crosses rho_crit with rho >= rho_crit just
//     below (scanned downward from above the column's highest particle in steps of vertical_step, then
//     bisected). Where a column has several crossings (overhangs, fallback clumps, a gap under a
//     clump) the topmost one is the surface: the surface as seen from above. NaN where no material
//     reaches rho_crit (outside the target, or a hole through it);
//   * rho0, the density on the pre-impact plane z = 0.
//
// The crater edge along one ray ("search inward from the rim crest", docs/physics.md section 5):
//   1. the wall: coming inward from max_radius, the first (outermost) sample whose surface lies more
//      than wall_depth below z = 0. Everything inside it (the floor, fallback clumps on it) is never
//      looked at by the edge search;
//   2. the rim crest: the highest surface sample outside the wall;
//   3. the edge: between wall and crest, the radius where rho0 first reaches rho_crit going outward
//      from the wall (i.e. where the crater wall meets the pre-impact plane), bisected on rho(r, 0).
// A clump on the floor that reaches above z = 0 makes rho0 >= rho_crit inside the crater; a search
// outward from the centre would stop at it, this one cannot reach it. Taking the crossing next to the
// wall rather than the outermost crossing below the crest also keeps the edge well defined when the
// rim is low: an undisturbed plane reads rho0 = rho_crit up to lattice noise.
//
// Derived quantities:
//   crater_radius       mean of the +x, -x, +y, -y edge radii (docs/physics.md section 5);
//   uncertainty         sqrt((s/2)^2 + (spacing/2)^2): s the sample standard deviation of the four radii
//                       (s/2 the standard error of their mean) and half a particle spacing for the
//                       resolution of a particle surface (on a graded target the local spacing at the
//                       crater radius);
//   depth               -(lowest surface sample inside the edge of its ray): apparent depth below z = 0;
//   profile z(r)        the surface height averaged over the azimuths at each r (NaN samples skipped);
//   rim height/radius   maximum of the azimuthal profile outside the crater radius, and where;
//   wall slope          least-squares slope (degrees) of the profile inside the crater radius between 20
//                       and 80 % of the depth: the wall without its rounded edge and the floor;
//   volume              sum over samples inside the edge of their ray of max(0, -z_s) r dr dphi: the
//                       apparent crater volume below the pre-impact plane (fallback material reduces it);
//   ejected mass        total mass of particles flagged particle_ejected (and per material id; four
//                       times that with quarter_symmetric);
//   boulders            mass-weighted centre of each boulder's non-ejected particles minus its
//                       initial centre.
// Without a rim the plane density approaches rho_crit from below outside the wall and the edge is
// ill-conditioned (up to 2 h too large): a warning says so when a directional crest is below spacing/4.
//
// Graded targets (options inner_spacing, inner_radius, grading): the sample radii are spaced dx(r)/4, the
// vertical scan step is dx(r)/4 and the wall depth dx(r) at each sample radius r (unless given), with
// dx(r) the set-up's local spacing (graded_spacing.hpp), so that a small crater in the fine core is seen
// at the core's resolution and the coarse outer target is not sampled needlessly finely.
//
// Cost: particles are binned into a sparse 2-D grid of vertical columns (edge 2 h, h the 99.9th
// percentile of the smoothing lengths; the few larger-h particles are checked for every column). Each
// sample column gathers its candidates once, grouped by smoothing length (factors of 2) and sorted by
// height within each group, so a density evaluation along the column touches only particles within
// their group's 2 h_max in z (one group when h is uniform). Columns are independent: OpenMP over samples.
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "craterkit/impact/graded_spacing.hpp"
#include "craterkit/sph/particles/kernel.hpp"
#include "craterkit/sph/particles/particles.hpp"

namespace craterkit::impact {

// A boulder to track: its particles are selected by id (when `ids` is not empty) or by material id.
struct BoulderSpec {
  std::string name;
  std::array<double, 3> initial_centre{0.0, 0.0, 0.0};  // m (mass-weighted centre at the start)
  std::vector<std::uint64_t> ids;                       // particle ids (any order)
  int material = -1;                                    // used when ids is empty (>= 0)
};

// The ids and the mass-weighted centre of the particles of `initial` for which select(i) is true
// (e.g. the particles inside a boulder's shape at t = 0).
template <class Select>
BoulderSpec boulder_from_particles(const sph::Particles& initial, std::string name, Select&& select) {
  BoulderSpec spec;
  spec.name = std::move(name);
  double m = 0.0;
  std::array<double, 3> c{0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < initial.size(); ++i) {
    if (!select(i)) continue;
    spec.ids.push_back(initial.id[i]);
    m += initial.mass[i];
    c[0] += initial.mass[i] * initial.x[i];
    c[1] += initial.mass[i] * initial.y[i];
    c[2] += initial.mass[i] * initial.z[i];
  }
  if (m > 0.0) spec.initial_centre = {c[0] / m, c[1] / m, c[2] / m};
  return spec;
}

struct CraterMeasurementOptions {
  double rho_initial = 0.0;       // kg/m^3, initial bulk density of the homogeneous matrix (> 0)
  double particle_spacing = 0.0;  // m, initial lattice spacing (> 0): sets the default resolutions
  // Graded-resolution target (graded_spacing.hpp; the impact set-up's inner_spacing, inner_radius,
  // grading and far coarsening, particle_spacing the outer spacing): the defaulted radial, vertical and
  // wall-depth steps, the rim warning and the resolution term of the uncertainty then follow the local
  // spacing dx(r) at each sample radius instead of particle_spacing. 0: uniform.
  double inner_spacing = 0.0;  // m
  double inner_radius = 0.0;   // m
  double grading = 0.0;
  double far_radius = 0.0, far_spacing = 0.0;              // m, the far coarsening (0: none)
  sph::KernelType kernel = sph::KernelType::cubic_spline;  // the kernel of the simulation
  std::array<double, 2> centre{0.0, 0.0};                  // m, impact point (x, y) on the pre-impact plane
  double max_radius = 0.0;      // m, outer end of every ray; 0: (horizontal extent of the target
                                // about the centre) - 2 h_max - spacing
  std::size_t n_azimuths = 64;  // rays (multiple of 4, >= 4)
  double radial_step = 0.0;     // m; 0: spacing / 4
  double vertical_step = 0.0;   // m, downward scan step of the surface search; 0: spacing / 4
  double wall_depth = 0.0;      // m, a wall sample lies this far below z = 0; 0: one spacing
  // The particles fill only x >= centre x, y >= centre y of a target symmetric about both planes (a
  // quarter-domain run with mirror boundaries, docs/physics.md section 4): their mirror images are added
  // to the density, and the ejected mass is reported for the full crater (4 x the quarter's).
  bool quarter_symmetric = false;
  std::vector<BoulderSpec> boulders;
};

// Per-ray result (radii in m from the centre, heights in m relative to z = 0).
struct RayMeasurement {
  double azimuth = 0.0;       // rad, from +x towards +y
  double edge_radius = 0.0;   // NaN when no crater was found on this ray
  double crest_radius = 0.0;  // rim crest outside the wall
  double crest_height = 0.0;
  double wall_radius = 0.0;  // outermost sample deeper than wall_depth
};

struct ProfileSample {
  double radius = 0.0;       // m
  double mean_height = 0.0;  // m, azimuthal mean of z_s (NaN when no azimuth has a surface)
  double min_height = 0.0;
  double max_height = 0.0;
  std::size_t azimuths = 0;  // azimuths with a surface at this radius
};

struct BoulderDisplacement {
  std::string name;
  std::array<double, 3> initial_centre{};
  std::array<double, 3> centre{};        // NaN when none of its particles remains
  std::array<double, 3> displacement{};  // centre - initial_centre
  double displacement_magnitude = 0.0;
  std::size_t particles = 0;  // non-ejected particles found
  double mass = 0.0;          // their mass, kg
  double ejected_mass = 0.0;  // mass of its particles flagged ejected, kg
};

struct CraterMeasurement {
  double crater_radius = 0.0;              // m, mean of the four directional radii (NaN if any is)
  double crater_radius_uncertainty = 0.0;  // m
  double radius_spread = 0.0;              // m, sample standard deviation of the four radii
  std::array<double, 4> radii{};           // m: +x, -x, +y, -y
  double mean_azimuthal_radius = 0.0;      // m, mean edge radius over all rays with an edge
  // Shape of the edge over all rays (boulders, oblique impacts): the shortest and longest edge radius and
  // the azimuths of their rays (rad, from +x towards +y), and the offset of the outline's centre from the
  // impact point, the first Fourier harmonic of the edge radius ((2/n) sum R cos phi, (2/n) sum R sin phi):
  // a circle of radius R0 whose centre is shifted by d << R0 has R(phi) = R0 + d cos(phi - phi_d) to first
  // order. The offset is NaN when a ray has no edge; the extremes are NaN when none has.
  double min_edge_radius = 0.0, min_edge_azimuth = 0.0;
  double max_edge_radius = 0.0, max_edge_azimuth = 0.0;
  std::array<double, 2> outline_centre_offset{};  // m (x, y)
  double depth = 0.0;                             // m, below z = 0
  double rim_height = 0.0;                        // m, maximum of the profile outside the crater radius
  double rim_radius = 0.0;                        // m
  // degrees: least-squares slope of the profile inside the crater radius between 20 and 80 % of the depth
  double wall_slope = 0.0;
  double volume = 0.0;                // m^3, below z = 0 and inside the edge
  double ejected_mass = 0.0;          // kg
  std::size_t ejected_particles = 0;  // particles flagged ejected in the set (not scaled by symmetry)
  std::vector<std::pair<int, double>> ejected_mass_by_material;  // (material id, kg)
  std::vector<RayMeasurement> rays;                              // n_azimuths
  std::vector<ProfileSample> profile;
  std::vector<BoulderDisplacement> boulders;
  std::vector<std::string> warnings;
  // The settings actually used (defaults resolved).
  double rho_initial = 0.0, rho_crit = 0.0, particle_spacing = 0.0;
  // radial_step, vertical_step and wall_depth: their values at the centre (on a graded target, defaulted
  // ones scale with the local spacing, dx(r) / inner_spacing).
  double max_radius = 0.0, radial_step = 0.0, vertical_step = 0.0, wall_depth = 0.0;
  double inner_spacing = 0.0, inner_radius = 0.0, grading = 0.0;  // uniform: particle_spacing, 0, 0
  std::array<double, 2> centre{};
  sph::KernelType kernel = sph::KernelType::cubic_spline;
  bool quarter_symmetric = false;
};

// Throws craterkit::InputError naming the option when an option is out of range (rho_initial,
// particle_spacing, n_azimuths, negative steps), or when no particle is left once ejecta are removed.
CraterMeasurement measure_crater(const sph::Particles& particles, const CraterMeasurementOptions& options);

// Interpolated, unnormalised density sum_j m_j W(|x - x_j|, h_j) over non-ejected particles at each
// point (brute force over the particles: for tests and spot checks, not for production sizes).
double interpolated_density_direct(const sph::Particles& particles, sph::KernelType kernel, double x,
                                   double y, double z);

// The surface height z_s at (x, y) and the density on z = 0 there, by the same column search as
// measure_crater (for tests and tools). NaN height where no material reaches rho_crit.
struct ColumnSample {
  double surface_height;
  double plane_density;
};
std::vector<ColumnSample> sample_columns(const sph::Particles& particles, sph::KernelType kernel,
                                         double rho_crit, double vertical_step,
                                         const std::vector<std::array<double, 2>>& xy);

// crater.json (see docs/crater_measurement.md) as a JSON text; `time` (s) is written when finite.
std::string crater_json_text(const CraterMeasurement& m, double time);
// crater_profile.csv: header and one row per profile radius.
std::string crater_profile_csv_text(const CraterMeasurement& m);
// Writes DIR/crater.json and DIR/crater_profile.csv atomically (creating DIR).
void write_crater_files(const std::filesystem::path& directory, const CraterMeasurement& m, double time);

}  // namespace craterkit::impact
