#pragma once
// The impact scenario of docs/physics.md section 4: a projectile striking a porous, lithostatically
// loaded half-space target cut to a hemisphere, with optional boulders. Defaults are the Hayabusa2 SCI
// case. Documented for users in docs/impact_setup.md.
//
// Geometry (z up, impact point at the origin, pre-impact surface z = 0):
//  - Lattice: simple cubic, spacing dx, nodes at ((i + 1/2) dx, (j + 1/2) dx, -(k + 1/2) dx) for integer
//    i, j, k. The top target layer lies at z = -dx/2 (each particle stands for the cell
//    [x - dx/2, x + dx/2]^3, so the cells fill z < 0 exactly), and the lattice is symmetric about the planes
//    x = 0 and y = 0, so the quarter domain x > 0, y > 0 is exactly a quarter of the full one.
//  - Target: every node with z < 0 and |x| < R_dom (the hemisphere); nodes above z = 0 only where a
//    boulder is (boulders may stick out of the surface), also within |x| < R_dom.
//  - Fixed shell: every target or boulder node with |x| > R_dom - shell_thickness is flagged
//    particle_fixed (shell_thickness default: 2 h = 2 eta dx, the kernel support, so a moving particle
//    never sees the missing material beyond the domain). The planes x = 0 and y = 0 of the quarter domain
//    are not a shell: they are mirror planes of the box (Box::mirror), whose images the neighbour search
//    generates (mirror_image.hpp); `symmetry` in the run attributes tells the crater measurement.
//  - Boulders: a node inside a boulder's Shape (shapes.hpp) gets the boulder's material; the first boulder
//    in the list wins where two overlap. Each boulder has its own entry in the material table (ids 2, 3,
//    ...: the crater measurement tracks boulders by material id).
//  - Projectile (material id 1): a sphere of radius a_p filled with the nodes of a cubic lattice of the same
//    spacing centred on the sphere's centre ((i + 1/2) dx offsets again), each of mass m_p / N (N nodes in
//    the full sphere), so the total mass and hence the momentum and energy are exact. "Touching the
//    surface at t = 0": the continuum sphere touches the continuum surface z = 0 at the impact point, i.e.
//    its centre is at (0, 0, a_p) whatever the impact angle. With a_p = 2 dx the lowest projectile layer
//    is then at z = +dx/2, one spacing above the top target layer, as in the lattice itself.
//  - Velocity: speed U at angle theta from the vertical, moving towards +x: U (sin theta, 0, -cos theta).
//
// Projectile model (docs/physics.md section 4):
//  - resolved: the real projectile, radius a = (3 m / (4 pi delta))^(1/3), density delta, mass m.
//  - point_source_stand_in: where a is too small for the lattice, a sphere of radius a_s (default
//    max(a, 2 dx)) with the same point-source coupling parameter a delta^nu U^mu at the same U:
//        delta_s = delta (a / a_s)^(1/nu),   m_s = m (a_s / a)^(3 - 1/nu)   (nu = 0.4: m_s = m sqrt(a_s/a)),
//    so its momentum and kinetic energy are larger by the same factor (a_s/a)^(3 - 1/nu). The crater of the
//    point-source law depends on the impactor only through a delta^nu at fixed U: in the gravity regime
//    R ∝ (a delta^nu)^(2/(2+mu)), in the strength regime R ∝ a delta^nu; a stand-in of the same MASS and a
//    larger radius would make a much smaller crater. a_s is chosen from the lattice, never from a crater
//    size. The stand-in's material is the projectile material with its density scaled by
//    k = delta_s / delta0 and every stress-like parameter (Tillotson rho0, A, B; shear modulus; yield
//    strength, cohesion, limiting strength, crush pressures) scaled by the same k: wave speeds and the
//    Hugoniot in velocity space (shock and particle velocities, compression) are those of the original.
//
// Graded resolution (inner_spacing > 0; graded_target.hpp, docs/impact_setup.md "Graded resolution"):
//  - the target (and the parts of boulders) is the graded point set instead of the lattice: a cubic core
//    of spacing dx0 = inner_spacing for r < R_c = inner_radius, hemispherical shells outside whose spacing
//    grows by the factor (1 + grading) per shell up to dx_max = particle_spacing, then dx_max out to R_dom;
//    each particle stands for its cell (volume V), mass rho V, h = eta V^(1/3);
//  - above z = 0 the points are the mirror images (x, y, -z) of those below, kept only inside boulders:
//    the boulders sticking out of the surface get the graded target's local spacing, continuous across
//    z = 0 (rather than a cubic lattice of one spacing, which could not match a boulder that spans a range
//    of local spacings and would leave an internal interface between two arrangements in the boulder);
//  - the projectile's lattice has the core spacing dx0 (resolved needs a >= 2 dx0; the stand-in's default
//    radius is max(a, 2 dx0));
//  - lithostatic state per particle, integrated down its own column (x, y) from the top of the material
//    above it (z = 0, or the top of a boulder) through the materials met (lithostatic_pressure_adaptive);
//  - far coarsening (far_radius r_f > 0): from the first shell at or beyond r_f the shells grow again by
//    (1 + grading) per shell up to dx_far = far_spacing, so that the particles far from the crater, which
//    barely move but cost the late stage most of its particle updates, are fewer and take longer steps;
//  - the fixed shell is r > R_dom - shell_thickness as on the lattice (default 2 eta dx, dx the spacing at
//    R_dom: dx_max, or with the far coarsening the last shell's).
//
// Initial state: lithostatic (lithostatic.hpp), integrated down each lattice column from the top of its
// highest node through the materials it meets; bulk density from the EOS at E = 0, distention alpha0
// (alpha_c(P), which is alpha0 below P_e), S = 0, E = 0, v = 0; mass rho dx^3; h = eta dx (the projectile:
// eta (m/rho)^(1/3)). Sound speed and pressure from material_response.hpp's evaluate_material().
//
// Late-stage transition (docs/physics.md section 3): t_transition defaults to 10 L / c with L = R_dom and c
// the bulk sound speed of the undisturbed porous target at the surface (evaluate_material at alpha0, E = 0):
// 10 x 15 m / 1500 m/s = 0.1 s for SCI. A_low defaults to 0.027 MPa (Jutzi et al. 2022). The set-up only
// computes and records them; the switch is the engine's.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "craterkit/impact/shapes.hpp"
#include "craterkit/sph/physics/material.hpp"
#include "craterkit/sph/solver/problem.hpp"

namespace craterkit::impact {

enum class ProjectileModel { resolved, point_source_stand_in };
enum class DomainSymmetry { full, quarter };

struct ImpactBoulder {
  std::string name;
  std::string material = "boulder";
  Shape shape;
};

struct ImpactSetup {
  std::string target_material = "basalt_matrix_ryugu";
  std::string projectile_material = "aluminium_projectile";
  double projectile_mass = 2.0;        // m, kg
  double projectile_density = 2700.0;  // delta, kg/m^3 (2 kg -> a = 5.6 cm)
  double impact_speed = 2000.0;        // U, m/s
  double impact_angle = 0.0;           // theta from the vertical, degrees, [0, 90)
  ProjectileModel projectile_model = ProjectileModel::point_source_stand_in;
  double stand_in_radius = 0.0;    // a_s, m; 0: max(a, 2 dx)
  double coupling_exponent = 0.4;  // nu of the coupling parameter a delta^nu U^mu
  double domain_radius = 15.0;     // R_dom, m
  double particle_spacing = 0.25;  // dx, m (graded: the outer, largest spacing dx_max)
  double inner_spacing = 0.0;      // dx0, m; 0: uniform lattice; 0 < dx0 < particle_spacing: graded
  double grading = 0.06;           // s, growth of the spacing per spacing outward, (0, 0.2] (graded)
  double inner_radius = 0.0;       // R_c, m, the uniform core (graded); 0: 8 dx0; >= 4 dx0
  double far_radius = 0.0;   // r_f, m (graded): beyond it the spacing grows again to far_spacing; 0: none
  double far_spacing = 0.0;  // dx_far, m, > particle_spacing (with far_radius)
  double fixed_shell_thickness = 0.0;  // m; 0: 2 eta dx (two smoothing lengths, the kernel support)
  DomainSymmetry symmetry = DomainSymmetry::full;
  double transition_time = 0.0;              // t_transition, s; 0: 10 R_dom / c
  double low_sound_speed_modulus = 0.027e6;  // A_low, Pa
  bool tensile_porosity = false;  // after the switch porous material opens pores in tension (late_stage.hpp)
  double escape_speed = 0.0;      // m/s, the body's; 0: ejecta only by leaving the domain (ejecta.hpp)
  std::vector<ImpactBoulder> boulders;
};

// What the set-up chose and derived: for the engine, the snapshot attributes and the printed summary.
struct ImpactSummary {
  // The real projectile.
  double projectile_mass = 0.0;             // kg
  double projectile_density = 0.0;          // kg/m^3
  double projectile_radius = 0.0;           // a, m
  double impact_speed = 0.0;                // m/s
  double impact_angle = 0.0;                // degrees from the vertical
  std::array<double, 3> impact_velocity{};  // m/s
  // The particle projectile (= the real one for the resolved model).
  ProjectileModel model = ProjectileModel::resolved;
  double coupling_exponent = 0.4;             // nu
  double model_radius = 0.0;                  // m
  double model_density = 0.0;                 // kg/m^3
  double model_mass = 0.0;                    // kg (the full sphere, also with quarter symmetry)
  double model_density_scale = 1.0;           // k = model density / projectile material reference density
  std::array<double, 3> projectile_centre{};  // m, at t = 0
  // The target.
  double domain_radius = 0.0, particle_spacing = 0.0, fixed_shell_thickness = 0.0, smoothing_length = 0.0;
  // Graded resolution. Uniform lattice: inner_spacing = particle_spacing, grading = 0, inner_radius = 0.
  bool graded = false;
  double inner_spacing = 0.0;  // dx0, m (the projectile's lattice spacing, also when uniform)
  double grading = 0.0;        // s
  double inner_radius = 0.0;   // R_c, m
  double core_radius = 0.0;    // rho_0, m: the hemisphere with the volume of the core cells
  double graded_radius = 0.0;  // m, where the shells reach the outer spacing (end of the graded zone)
  double far_radius = 0.0, far_spacing = 0.0;  // m (0: no far coarsening)
  double far_shells_radius = 0.0;              // m, inner edge of the first shell thicker than dx_max
  std::size_t shells = 0, graded_shells = 0, coarse_shells = 0;
  double min_smoothing_length = 0.0, max_smoothing_length = 0.0;  // m, over the target and boulders
  double gravity = 0.0;                                           // g, m/s^2 (gravity vector (0, 0, -g))
  double initial_bulk_density = 0.0;      // rho0 / alpha0 of the target at P = 0, kg/m^3
  double initial_distention = 1.0;        // alpha0
  double initial_sound_speed = 0.0;       // c of the undisturbed target at the surface, m/s
  double max_lithostatic_pressure = 0.0;  // Pa
  DomainSymmetry symmetry = DomainSymmetry::full;
  double transition_time = 0.0;  // s
  bool transition_time_from_rule = true;
  double low_sound_speed_modulus = 0.0;  // Pa
  double escape_speed = 0.0;             // m/s (0: not used)
  // Particle counts.
  std::size_t target_particles = 0;      // matrix, including fixed
  std::size_t core_particles = 0;        // graded: target and boulder particles of the uniform core
  std::size_t fixed_particles = 0;       // all materials
  std::size_t projectile_particles = 0;  // in this domain (a quarter of the sphere's with quarter symmetry)
  std::vector<std::size_t> boulder_particles;  // per boulder, including fixed
  std::vector<std::string> boulder_names;
  std::vector<std::uint16_t> boulder_material_ids;
  std::size_t total_particles = 0;
};

struct ImpactScenario {
  sph::ProblemSetup problem;  // materials: [0] target, [1] projectile (or stand-in), [2 + b] boulder b
  ImpactSummary summary;
};

// eta: h = eta (m/rho)^(1/3); alpha: the initial artificial-viscosity coefficient; gravity: the run's
// gravity vector, which must be (0, 0, -g) with g >= 0. Throws craterkit::InputError naming the
// impact.<key> for an impossible set-up (e.g. an unresolvable projectile with projectile_model =
// "resolved", quarter symmetry with boulders or an oblique impact, a boulder overlapping the projectile).
ImpactScenario make_impact(const ImpactSetup& setup, double eta, double alpha,
                           const std::array<double, 3>& gravity);

// The projectile alone (radius, stand-in, velocity, centre) without building the target: what
// make_impact() puts into the summary. Throws as make_impact() for the projectile keys.
ImpactSummary impact_projectile_summary(const ImpactSetup& setup, double projectile_reference_density);

// The projectile material with density and every stress-like parameter scaled by k (header comment).
sph::Material density_scaled_material(const sph::Material& material, double k);

// A few lines saying what was chosen (projectile model and stand-in, counts, t_transition), for the log.
std::string describe_impact(const ImpactSummary& summary);

[[nodiscard]] std::string symmetry_name(DomainSymmetry symmetry);
[[nodiscard]] std::string projectile_model_name(ProjectileModel model);

}  // namespace craterkit::impact
