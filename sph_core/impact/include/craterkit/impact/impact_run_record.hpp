#pragma once
// The record of an impact run: what the set-up chose that a reader of its snapshots needs, above all
// everything that decides how its crater is measured. Written into every snapshot and checkpoint as named
// attributes (docs/output.md, docs/impact_setup.md) and read back by `craterkit measure`, through the one
// mapping of this header, so that measuring a run's snapshot gives the crater the run measured.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "craterkit/impact/crater_measurement.hpp"
#include "craterkit/impact/impact_setup.hpp"
#include "craterkit/sph/io/snapshot.hpp"
#include "craterkit/sph/particles/kernel.hpp"
#include "craterkit/sph/particles/particles.hpp"

namespace craterkit::impact {

// A boulder as the crater measurement tracks it: its particles (those of its material id) and their
// mass-weighted centre at t = 0.
struct RecordedBoulder {
  std::string name;
  std::uint16_t material = 0;
  std::array<double, 3> initial_centre{0.0, 0.0, 0.0};  // m
};

struct ImpactRunRecord {
  // The target and its resolution.
  double initial_bulk_density = 0.0;  // kg/m^3, rho0 / alpha0 of the target at P = 0
  double initial_sound_speed = 0.0;   // m/s, of the undisturbed target at the surface
  double particle_spacing = 0.0;      // m (graded target: the outer spacing dx_max)
  double inner_spacing = 0.0;         // m; the projectile's lattice spacing (= particle_spacing when uniform)
  double grading = 0.0;               // growth of the spacing per spacing outward (0: uniform)
  double inner_radius = 0.0;          // m, the uniform core of a graded target (0 when uniform)
  double far_radius = 0.0, far_spacing = 0.0;  // m, the far coarsening (0: none; absent from older files)
  double domain_radius = 0.0;                  // m
  double fixed_shell_thickness = 0.0;          // m
  double gravity = 0.0;                        // m/s^2, downward
  double escape_speed = 0.0;                   // m/s (0: not used)
  sph::KernelType kernel = sph::KernelType::cubic_spline;
  DomainSymmetry symmetry = DomainSymmetry::full;
  std::vector<RecordedBoulder> boulders;
  // The projectile and its particle model.
  double projectile_radius = 0.0, projectile_mass = 0.0, projectile_density = 0.0;  // m, kg, kg/m^3
  double impact_speed = 0.0;                                                        // m/s
  double impact_angle = 0.0;  // degrees from the vertical
  ProjectileModel projectile_model = ProjectileModel::resolved;
  double coupling_exponent = 0.4;
  double stand_in_radius = 0.0, stand_in_density = 0.0, stand_in_mass = 0.0, stand_in_density_scale = 1.0;
  // The late stage.
  double transition_time = 0.0;   // s
  double A_low = 0.0;             // Pa, of the target
  double A_low_projectile = 0.0;  // Pa, of the projectile (scaled with a stand-in's density)

  [[nodiscard]] bool graded() const { return grading > 0.0; }
};

// The record of a set-up: `initial` is its particle set at t = 0 (for the boulders' centres).
ImpactRunRecord make_run_record(const ImpactSummary& summary, sph::KernelType kernel,
                                const sph::Particles& initial, double A_low_projectile);

// As attributes (with the text setup = "impact"), and back. read_run_record throws craterkit::InputError
// naming `source` and the first missing attribute.
sph::RunAttributes run_record_attributes(const ImpactRunRecord& record);
ImpactRunRecord read_run_record(const sph::RunAttributes& attributes, const std::string& source);
// Whether the attributes are those of an impact run (setup = "impact").
[[nodiscard]] bool is_impact_run(const sph::RunAttributes& attributes);

// How the crater of this run is measured: its density, spacings (graded or uniform), kernel, symmetry,
// boulders, and rays that end at the inner face of the fixed shell (the default, from the particles' extent
// and the largest h, is thrown off by isolated particles with large h above the target).
CraterMeasurementOptions crater_measurement_options(const ImpactRunRecord& record);

}  // namespace craterkit::impact
