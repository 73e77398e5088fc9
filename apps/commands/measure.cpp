// craterkit measure: the crater of an SPH snapshot (docs/physics.md section 5), printed, and with --out
// written as crater.json and crater_profile.csv (formats in docs/crater_measurement.md). The snapshot of an
// impact run is measured as the run measured it (its run record: impact/impact_run_record.hpp); flags
// override.
#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/impact/impact_run_record.hpp"
#include "craterkit/sph/io/snapshot.hpp"
#include "output_checks.hpp"

namespace craterkit::cli {
namespace {

struct MeasureOptions {
  std::string snapshot;
  std::optional<double> rho_initial;
  std::optional<double> spacing;
  std::optional<std::string> kernel;
  std::vector<double> centre;
  std::optional<double> max_radius;
  std::size_t azimuths = 64;
  double radial_step = 0.0;
  double wall_depth = 0.0;
  bool quarter = false;
  std::optional<std::string> boulders;
  std::optional<std::string> out;
  bool json = false;
};

double positive_flag(double value, const char* flag) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw InputError(fmt::format("{} {} is not allowed: must be a finite number > 0", flag, value));
  }
  return value;
}

sph::KernelType parse_kernel(const std::string& name, const std::string& where) {
  if (name == "cubic_spline") return sph::KernelType::cubic_spline;
  if (name == "wendland_c2") return sph::KernelType::wendland_c2;
  throw InputError(where + " '" + name + "' is not allowed: use cubic_spline or wendland_c2");
}

// --boulders FILE.json: [{"name": "1", "initial_centre": [x, y, z], "material": 2}, or with
// "ids": [..] or "id_range": [first, last] (inclusive) instead of "material"].
std::vector<impact::BoulderSpec> read_boulders(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("--boulders " + path + ": cannot open the file");
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError("--boulders " + path + ": not valid JSON (" + e.what() + ")");
  }
  if (!doc.is_array()) throw InputError("--boulders " + path + ": must be a JSON array of boulder objects");
  std::vector<impact::BoulderSpec> out;
  for (std::size_t k = 0; k < doc.size(); ++k) {
    const auto& b = doc[k];
    const std::string where = fmt::format("--boulders {} entry {}", path, k);
    if (!b.is_object()) throw InputError(where + ": must be an object");
    for (const auto& [key, value] : b.items()) {
      if (key != "name" && key != "initial_centre" && key != "material" && key != "ids" &&
          key != "id_range") {
        throw InputError(where + ": unknown key '" + key +
                         "' (allowed: name, initial_centre, material, ids, id_range)");
      }
    }
    impact::BoulderSpec spec;
    try {
      spec.name = b.value("name", std::to_string(k + 1));
      const auto centre = b.at("initial_centre").get<std::vector<double>>();
      if (centre.size() != 3) throw InputError(where + ": 'initial_centre' must hold 3 numbers (m)");
      spec.initial_centre = {centre[0], centre[1], centre[2]};
      const int selectors =
          int(b.contains("material")) + int(b.contains("ids")) + int(b.contains("id_range"));
      if (selectors != 1) throw InputError(where + ": give exactly one of 'material', 'ids', 'id_range'");
      if (b.contains("material")) {
        spec.material = b.at("material").get<int>();
        if (spec.material < 0) throw InputError(where + ": 'material' must be >= 0");
      } else if (b.contains("ids")) {
        spec.ids = b.at("ids").get<std::vector<std::uint64_t>>();
        if (spec.ids.empty()) throw InputError(where + ": 'ids' is empty");
      } else {
        const auto range = b.at("id_range").get<std::vector<std::uint64_t>>();
        if (range.size() != 2 || range[1] < range[0]) {
          throw InputError(where + ": 'id_range' must be [first, last] with first <= last");
        }
        for (std::uint64_t id = range[0]; id <= range[1]; ++id) spec.ids.push_back(id);
      }
    } catch (const nlohmann::json::exception& e) {
      throw InputError(where + ": " + e.what());
    }
    out.push_back(std::move(spec));
  }
  return out;
}

// The measurement of the run that wrote the snapshot (an impact's run record), or, for any other snapshot,
// what the flags give.
impact::CraterMeasurementOptions measurement_options(const MeasureOptions& options,
                                                     const sph::RunAttributes& attributes) {
  impact::CraterMeasurementOptions m;
  if (impact::is_impact_run(attributes)) {
    m = impact::crater_measurement_options(impact::read_run_record(attributes, options.snapshot));
  }
  if (options.rho_initial) m.rho_initial = positive_flag(*options.rho_initial, "--rho-initial");
  if (options.spacing) {
    // The snapshot's resolution overridden: uniform at this spacing.
    m.particle_spacing = positive_flag(*options.spacing, "--spacing");
    m.inner_spacing = m.inner_radius = m.grading = 0.0;
  }
  if (!(m.rho_initial > 0.0)) {
    throw InputError(options.snapshot + " is not the snapshot of an impact run: give --rho-initial");
  }
  if (!(m.particle_spacing > 0.0)) {
    throw InputError(options.snapshot + " is not the snapshot of an impact run: give --spacing");
  }
  if (options.kernel) m.kernel = parse_kernel(*options.kernel, "--kernel");
  if (!options.centre.empty()) {
    if (options.centre.size() != 2) throw InputError("--centre takes two numbers X Y (m)");
    m.centre = {options.centre[0], options.centre[1]};
  }
  m.quarter_symmetric = m.quarter_symmetric || options.quarter;
  if (options.azimuths < 4 || options.azimuths % 4 != 0 || options.azimuths > 3600) {
    throw InputError(fmt::format("--azimuths {} is not allowed: must be a multiple of 4 from 4 to 3600",
                                 options.azimuths));
  }
  for (const auto& [flag, value] :
       {std::pair{"--max-radius", options.max_radius.value_or(0.0)},
        std::pair{"--radial-step", options.radial_step}, std::pair{"--wall-depth", options.wall_depth}}) {
    if (!(value >= 0.0) || !std::isfinite(value)) {
      throw InputError(fmt::format(
          "{} {} is not allowed: must be a finite number >= 0 (m; 0 selects the default)", flag, value));
    }
  }
  if (options.max_radius) m.max_radius = *options.max_radius;
  m.n_azimuths = options.azimuths;
  m.radial_step = options.radial_step;
  m.wall_depth = options.wall_depth;
  if (options.boulders) m.boulders = read_boulders(*options.boulders);
  return m;
}

void run_measure(const MeasureOptions& options) {
  if (options.out) check_output_folder("--out", *options.out);
  sph::RunAttributes attributes;
  const sph::Particles particles = sph::read_snapshot(options.snapshot, &attributes);
  const impact::CraterMeasurement result =
      impact::measure_crater(particles, measurement_options(options, attributes));
  if (options.out) impact::write_crater_files(*options.out, result, attributes.time);

  if (options.json) {
    std::cout << impact::crater_json_text(result, attributes.time);
    return;
  }
  fmt::print("Crater of {} (t = {:.6g} s, {} particles, {} ejected)\n", options.snapshot, attributes.time,
             particles.size(), result.ejected_particles);
  fmt::print("  crater radius {:.4g} +- {:.2g} m  (+x {:.4g}, -x {:.4g}, +y {:.4g}, -y {:.4g})\n",
             result.crater_radius, result.crater_radius_uncertainty, result.radii[0], result.radii[1],
             result.radii[2], result.radii[3]);
  fmt::print(
      "  depth {:.4g} m, rim height {:.4g} m at r = {:.4g} m, wall slope {:.3g} deg, volume {:.4g} m^3, "
      "ejected mass {:.4g} kg\n",
      result.depth, result.rim_height, result.rim_radius, result.wall_slope, result.volume,
      result.ejected_mass);
  for (const auto& b : result.boulders) {
    fmt::print("  boulder {}: displaced by {:.4g} m ({:.4g}, {:.4g}, {:.4g})\n", b.name,
               b.displacement_magnitude, b.displacement[0], b.displacement[1], b.displacement[2]);
  }
  for (const auto& w : result.warnings) fmt::print("  warning: {}\n", w);
  if (options.out) {
    const std::filesystem::path directory(*options.out);
    fmt::print("  wrote {} and {}\n", (directory / "crater.json").string(),
               (directory / "crater_profile.csv").string());
  }
}

void add_measure_command(CLI::App& parent) {
  auto options = std::make_shared<MeasureOptions>();
  auto* sub = parent.add_subcommand(
      "measure",
      "Measure the crater of an SPH snapshot (radius at the pre-impact level, depth, rim, profile)");
  sub->add_option("snapshot", options->snapshot, "Snapshot (HDF5) written by craterkit simulate")->required();
  sub->add_option("--rho-initial", options->rho_initial,
                  "Initial bulk density of the target matrix, kg/m^3 (default: the impact run's)");
  sub->add_option(
      "--spacing", options->spacing,
      "Initial particle spacing, m; uniform (default: the impact run's, graded if its target was)");
  sub->add_option("--kernel", options->kernel,
                  "cubic_spline or wendland_c2 (default: the impact run's, else cubic_spline)");
  sub->add_option("--centre", options->centre, "Impact point X Y on the pre-impact plane, m (default 0 0)")
      ->expected(2);
  sub->add_option("--max-radius", options->max_radius,
                  "Outer end of the rays, m (default: the inner face of an impact run's fixed shell, else "
                  "target extent - 2 h - spacing)");
  sub->add_option("--azimuths", options->azimuths, "Number of rays (multiple of 4; default 64)");
  sub->add_option("--radial-step", options->radial_step, "Radial sample step, m (default (local) spacing/4)");
  sub->add_option("--wall-depth", options->wall_depth,
                  "Depth below z = 0 that marks the crater wall, m (default one (local) spacing)");
  sub->add_flag("--quarter", options->quarter,
                "Quarter-domain run mirrored at x = 0 and y = 0 (default: the impact run's symmetry)");
  sub->add_option(
      "--boulders", options->boulders,
      "JSON file: [{\"name\", \"initial_centre\": [x,y,z], \"material\" | \"ids\" | \"id_range\"}] "
      "(default: the impact run's boulders)");
  sub->add_option("--out", options->out,
                  "Write crater.json and crater_profile.csv into this directory (default: write nothing)");
  sub->add_flag("--json", options->json, "Print crater.json on stdout");
  sub->footer(
      "Method and file formats: docs/crater_measurement.md. Exit status 2 for bad input (the message "
      "names the flag or attribute).");
  sub->callback([options] { run_measure(*options); });
}

const bool measure_registered = register_command({"measure", 60, &add_measure_command});

}  // namespace
}  // namespace craterkit::cli
