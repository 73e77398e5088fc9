// craterkit dem-late-stage: an impact's late stage as a granular DEM run by LAMMPS, from a snapshot of an SPH
// impact run at the hand-off time (docs/dem.md, "Late stage"). Writes crater.json, crater_growth.csv,
// handoff.json and late_stage.json into --out, as an SPH impact run writes its crater.
#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <numbers>
#include <optional>
#include <string>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/dem_late_stage/dem_late_stage.hpp"
#include "craterkit/sph/physics/yield_strength.hpp"
#include "json_output.hpp"

namespace craterkit::cli {
namespace {

struct DemLateStageOptions {
  dem_late_stage::DemLateStageSpec spec;
  std::string out;
  std::optional<double> friction;
  bool json = false;
};

void run_dem_late_stage_command(DemLateStageOptions options) {
  if (options.friction) {
    // theta(f) of physics.md section 2: the angle at which a pile of the SPH material stands.
    if (!(*options.friction > 0.0) || !(*options.friction < std::sqrt(2.0)))
      throw InputError(fmt::format(
          "--friction {} is not allowed: the SPH friction coefficient, 0 < f < sqrt(2)", *options.friction));
    options.spec.repose_angle = sph::repose_angle_from_friction(*options.friction) * 180.0 / std::numbers::pi;
  }
  const auto result = dem_late_stage::run_dem_late_stage(
      options.spec, options.out, [](const std::string& line) { std::cerr << line << std::endl; });
  if (options.json) {
    print_json(nlohmann::json::parse(std::ifstream(std::filesystem::path(options.out) / "late_stage.json")));
    return;
  }
  std::cout << fmt::format(
      "crater radius {:.3f} +- {:.3f} m, depth {:.3f} m at t = {:g} s ({})\n", result.crater.crater_radius,
      result.crater.crater_radius_uncertainty, result.crater.depth, result.crater_time,
      result.growth_ended_sample ? "growth ended" : "growth had not ended by the end time");
}

void add_dem_late_stage_command(CLI::App& parent) {
  auto options = std::make_shared<DemLateStageOptions>();
  auto& spec = options->spec;
  auto* sub = parent.add_subcommand("dem-late-stage",
                                    "Continue an SPH impact run as a granular DEM (LAMMPS) from one of its "
                                    "snapshots and measure the crater "
                                    "on the grains");
  sub->add_option("snapshot", spec.snapshot,
                  "Snapshot (HDF5) of a quarter-domain impact run at the hand-off time")
      ->required();
  sub->add_option("--out", options->out,
                  "Directory for crater.json, crater_growth.csv, handoff.json, lammps/")
      ->required();
  sub->add_option("--grain-diameter", spec.grain_diameter,
                  "Mean grain diameter, m (sizes +-10 %; default 0.5)");
  sub->add_option("--bed-length", spec.bed_length,
                  "Bed extent along x and y from the impact point, m (default: the SPH run's domain radius)");
  sub->add_option("--bed-depth", spec.bed_depth, "Bed depth below the pre-impact plane, m (default 6)");
  sub->add_option("--bed-height", spec.bed_height,
                  "Bed above the plane before carving, for raised material, m (default 2)");
  sub->add_option("--friction", options->friction,
                  "The SPH material's friction coefficient f; sets the grains' angle of repose theta(f) "
                  "(default: 29.24 degrees, f = 0.55)");
  sub->add_option("--repose-angle", spec.repose_angle, "The grains' angle of repose, degrees (default 29.24)")
      ->excludes(sub->get_option("--friction"));
  sub->add_option("--restitution", spec.restitution, "Normal coefficient of restitution (default 0.5)");
  sub->add_option("--end-time", spec.end_time,
                  "Impact time at which the late stage ends at the latest, s (default 500)");
  sub->add_flag(
      "--stop-when-grown,!--no-stop-when-grown", spec.stop_when_grown,
      "Stop LAMMPS at the end of crater growth (the SPH run's rule; default), or run to --end-time");
  sub->add_option("--output-interval", spec.output_interval,
                  "Simulated time between crater samples, s (default 5)");
  sub->add_option(
      "--ejecta-speed", spec.ejecta_speed,
      "Rising material faster than this enters as flying grains, m/s (default: the run's escape speed)");
  sub->add_option("--seed", spec.seed, "Seed of the bed's grain sizes and lattice (default 1)");
  sub->add_option("--processes", spec.processes, "LAMMPS processes (mpirun when > 1; default 1)");
  sub->add_option("--bed-cache", spec.bed_cache, "Directory of settled beds (default OUT/beds)");
  sub->add_flag(
      "--remeasure", spec.remeasure,
      "Measure the dumps of an earlier run in --out again (same snapshot and options) without LAMMPS");
  sub->add_flag("--json", options->json, "Print late_stage.json (set-up, costs, crater) on stdout");
  sub->footer(
      "Needs LAMMPS (`lmp` on PATH, or CRATERKIT_LAMMPS). Method and files: docs/dem.md. Exit status 2 for "
      "bad input (the message names the option).");
  sub->callback([options] { run_dem_late_stage_command(*options); });
}

const bool dem_late_stage_registered = register_command({"dem-late-stage", 52, &add_dem_late_stage_command});

}  // namespace
}  // namespace craterkit::cli
