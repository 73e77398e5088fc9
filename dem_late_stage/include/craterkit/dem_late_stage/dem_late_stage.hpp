#pragma once
// An impact's late stage as a granular DEM run by LAMMPS, from an SPH snapshot of a quarter-domain impact run
// at the hand-off time (docs/dem.md, "Late stage"):
//   - a bed of grains (diameters uniform within +-10 % of `grain_diameter`) in the box x, y in [0, L] (L the
//   SPH
//     run's domain radius unless given),
//     from `bed_depth` below the pre-impact plane to `bed_height` above it, between frictionless walls,
//     settled under the run's gravity once and cached per set-up; its grain density chosen so that its bulk
//     density is the target's;
//   - contact friction from the SPH material's angle of repose (mu_s = 0.85, mu_r from the calibration table
//     data/dem/repose_calibration.csv), restitution as given; the bed settles with the stiffness for an
//     overlap of 1e-3 d under its weight (youngs_modulus_for_overlap), the run uses that or, when stiffer,
//     the one for which the flow's fastest grain hitting a grain at rest overlaps by 5 % of the smallest
//     diameter (youngs_modulus_for_impact);
//   - the hand-off (handoff.hpp), then LAMMPS with mirror walls at x = 0 and y = 0, the outer shell frozen,
//     fast ejecta ballistic, grains leaving the box lost (counted as ejected);
//   - the grains dumped every `output_interval`, each dump measured as an SPH snapshot is (grain_crater.hpp)
//     while LAMMPS runs, and LAMMPS stopped at the end of growth by the SPH run's rule (crater_growth.hpp),
//     or at `end_time`.
// Writes into `out`: handoff.json (the balance of the hand-off), crater_growth.csv, crater.json and
// crater_profile.csv (at the end of growth, or at the end time when growth did not end), late_stage.json
// (the set-up, the costs and the result), and lammps/ (script, data file, log, dumps).
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "craterkit/dem_late_stage/handoff.hpp"
#include "craterkit/impact/crater_growth.hpp"
#include "craterkit/impact/crater_measurement.hpp"

namespace craterkit::dem_late_stage {

struct DemLateStageSpec {
  std::filesystem::path snapshot;  // an impact run's snapshot (or checkpoint) at the hand-off time
  double grain_diameter = 0.5;     // m, the mean; sizes uniform within +-10 %
  double bed_length = 0.0;      // m, L: the bed's extent along x and along y from the impact point; 0: R_dom
  double bed_depth = 6.0;       // m below the pre-impact plane
  double bed_height = 2.0;      // m above it before carving (room for the material the SPH stage raised)
  double repose_angle = 29.24;  // degrees, of the SPH material (theta(f) of physics.md section 2)
  double restitution = 0.5;
  double end_time = 500.0;  // s, impact time at which LAMMPS stops at the latest
  // Stop LAMMPS at the end of growth (the SPH run's rule, applied to the dumps while it runs); false: run to
  // end_time, still reporting when growth ended.
  bool stop_when_grown = true;
  double output_interval = 5.0;  // s between crater samples
  double ejecta_speed = 0.0;     // m/s; 0: the SPH run's escape speed
  std::uint64_t seed = 1;
  int processes = 1;                   // LAMMPS processes (mpirun)
  std::filesystem::path bed_cache;     // settled beds; empty: out/beds
  std::filesystem::path repose_table;  // empty: data/dem/repose_calibration.csv
  // Measure the dumps of an earlier run in out/lammps again instead of running LAMMPS (the hand-off must be
  // the same: its data file is compared).
  bool remeasure = false;
};

struct DemLateStageResult {
  double handoff_time = 0.0;  // s
  HandoffBalance balance;
  // The impact at t = 0 (the projectile's kinetic energy in the quarter, no radius), then one per dump (step:
  // LAMMPS steps since the hand-off).
  std::vector<impact::CraterGrowthSample> samples;
  std::optional<std::size_t> growth_ended_sample;  // index into samples
  bool stopped_when_grown = false;                 // LAMMPS was asked to stop before end_time
  impact::CraterMeasurement crater;                // at the end of growth (or at the last sample)
  double crater_time = 0.0;                        // s
  double plane_height = 0.0;                       // m, the grains' pre-impact level
  std::size_t grains = 0;                          // handed over (all roles)
  double time_step = 0.0;                          // s
  double youngs_modulus = 0.0, sliding_friction = 0.0, rolling_friction = 0.0;  // Pa, -, - (the run's)
  // The elastic energy in the overlaps of the settled bed's contacts with the settling and the run's
  // stiffness.
  double bed_elastic_energy_settled = 0.0, bed_elastic_energy_run = 0.0;     // J
  double bulk_density = 0.0, grain_density = 0.0;                            // kg/m^3
  double settle_seconds = 0.0, lammps_seconds = 0.0, measure_seconds = 0.0;  // wall time
};

// InputError naming the option for a value out of range.
void check_dem_late_stage_spec(const DemLateStageSpec& spec);

// Runs the late stage; progress lines go to `progress` (may be empty).
DemLateStageResult run_dem_late_stage(const DemLateStageSpec& spec, const std::filesystem::path& out,
                                      const std::function<void(const std::string&)>& progress = {});

}  // namespace craterkit::dem_late_stage
