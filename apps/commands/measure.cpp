// craterkit measure: the crater of an SPH snapshot (physics.md section 5): crater.json and
// crater_profile.csv (formats in docs/crater_measurement.md).
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
#include "craterkit/impact/crater_measurement.hpp"
#include "craterkit/sph/io/snapshot.hpp"

namespace craterkit::cli {
namespace {

struct MeasureOptions {
  std::string snapshot;
  std::optional<double> rho_initial;
  std::optional<double> spacing;
  std::optional<std::string> kernel;
  std::vector<double> centre;
  double max_radius = 0.0;
  std::size_t azimuths = 64;
  double radial_step = 0.0;
  double wall_depth = 0.0;
  bool quarter = false;
  std::optional<std::string> boulders;
  std::optional<std::string> out;
  bool json = false;
};

// Snapshot attributes the simulation records for the measurement (RunAttributes::numbers / texts).
constexpr const char* attribute_rho_initial = "initial_bulk_density";  // kg/m^3
constexpr const char* attribute_spacing = "particle_spacing";          // m (graded: the outer spacing)
constexpr const char* attribute_inner_spacing = "inner_spacing";       // m, graded target's core spacing
constexpr const char* attribute_inner_radius = "inner_radius";         // m, graded target's core radius
constexpr const char* attribute_grading = "grading";                   // graded target's growth per spacing
constexpr const char* attribute_kernel = "kernel";                     // "cubic_spline" | "wendland_c2"
constexpr const char* attribute_symmetry = "symmetry";                 // "quarter": mirrored at x = 0, y = 0

double resolve_number(const std::optional<double>& flag_value, const sph::RunAttributes& attributes,
                      const char* attribute, const char* flag, const std::string& snapshot) {
  if (flag_value) {
    if (!(*flag_value > 0.0) || !std::isfinite(*flag_value)) {
      throw InputError(fmt::format("{} {} is not allowed: must be a finite number > 0", flag, *flag_value));
    }
    return *flag_value;
  }
  const auto it = attributes.numbers.find(attribute);
  if (it == attributes.numbers.end()) {
    throw InputError(
        fmt::format("{} has no attribute '{}': give {} on the command line", snapshot, attribute, flag));
  }
  if (!(it->second > 0.0) || !std::isfinite(it->second)) {
    throw InputError(fmt::format("{}: attribute '{}' = {} is not > 0: give {} on the command line", snapshot,
                                 attribute, it->second, flag));
  }
  return it->second;
}

sph::KernelType parse_kernel(const std::string& name, const std::string& where) {
  if (name == "cubic_spline") return sph::KernelType::cubic_spline;
  if (name == "wendland_c2") return sph::KernelType::wendland_c2;
  throw InputError(where + " '" + name + "' is not allowed: use cubic_spline or wendland_c2");
}

// --boulders FILE.json: [{"name": "1", "initial_centre": [x, y, z], "material": 2}, or with
// "ids": [..] or "id_range": [first, last] (inclusive) instead of "material"].
std::vector<sph::BoulderSpec> read_boulders(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError("--boulders " + path + ": cannot open the file");
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError("--boulders " + path + ": not valid JSON (" + e.what() + ")");
  }
  if (!doc.is_array()) throw InputError("--boulders " + path + ": must be a JSON array of boulder objects");
  std::vector<sph::BoulderSpec> out;
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
    sph::BoulderSpec spec;
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

void run_measure(const MeasureOptions& options) {
  sph::RunAttributes attributes;
  const sph::Particles particles = sph::read_snapshot(options.snapshot, &attributes);

  sph::CraterMeasurementOptions m;
  m.rho_initial = resolve_number(options.rho_initial, attributes, attribute_rho_initial, "--rho-initial",
                                 options.snapshot);
  m.particle_spacing =
      resolve_number(options.spacing, attributes, attribute_spacing, "--spacing", options.snapshot);
  // A graded target (docs/impact_setup.md "Graded resolution"): the measurement follows its local spacing,
  // unless --spacing overrides the snapshot's resolution (then uniform at that spacing).
  if (!options.spacing) {
    const auto number = [&](const char* name) {
      const auto it = attributes.numbers.find(name);
      return it == attributes.numbers.end() ? 0.0 : it->second;
    };
    m.inner_spacing = number(attribute_inner_spacing);
    m.inner_radius = number(attribute_inner_radius);
    m.grading = number(attribute_grading);
  }
  if (options.kernel) {
    m.kernel = parse_kernel(*options.kernel, "--kernel");
  } else if (const auto it = attributes.texts.find(attribute_kernel); it != attributes.texts.end()) {
    m.kernel = parse_kernel(it->second, options.snapshot + ": attribute 'kernel'");
  }
  if (!options.centre.empty()) {
    if (options.centre.size() != 2) throw InputError("--centre takes two numbers X Y (m)");
    m.centre = {options.centre[0], options.centre[1]};
  }
  const auto symmetry = attributes.texts.find(attribute_symmetry);
  m.quarter_symmetric =
      options.quarter || (symmetry != attributes.texts.end() && symmetry->second == "quarter");
  if (options.azimuths < 4 || options.azimuths % 4 != 0) {
    throw InputError(
        fmt::format("--azimuths {} is not allowed: must be a multiple of 4, >= 4", options.azimuths));
  }
  for (const auto& [flag, value] :
       {std::pair{"--max-radius", options.max_radius}, std::pair{"--radial-step", options.radial_step},
        std::pair{"--wall-depth", options.wall_depth}}) {
    if (!(value >= 0.0) || !std::isfinite(value)) {
      throw InputError(fmt::format(
          "{} {} is not allowed: must be a finite number >= 0 (m; 0 selects the default)", flag, value));
    }
  }
  m.max_radius = options.max_radius;
  m.n_azimuths = options.azimuths;
  m.radial_step = options.radial_step;
  m.wall_depth = options.wall_depth;
  if (options.boulders) m.boulders = read_boulders(*options.boulders);

  const sph::CraterMeasurement result = sph::measure_crater(particles, m);
  const std::filesystem::path directory = options.out ? std::filesystem::path(*options.out)
                                                      : std::filesystem::path(options.snapshot).parent_path();
  sph::write_crater_files(directory, result, attributes.time);

  if (options.json) {
    std::cout << sph::crater_json_text(result, attributes.time);
    return;
  }
  fmt::print("Crater of {} (t = {:.6g} s, {} particles, {} ejected)\n", options.snapshot, attributes.time,
             particles.size(), result.ejected_particles);
  fmt::print("  crater radius {:.4g} +- {:.2g} m  (+x {:.4g}, -x {:.4g}, +y {:.4g}, -y {:.4g})\n",
             result.crater_radius, result.crater_radius_uncertainty, result.radii[0], result.radii[1],
             result.radii[2], result.radii[3]);
  fmt::print(
      "  depth {:.4g} m, rim height {:.4g} m at r = {:.4g} m, volume {:.4g} m^3, ejected mass {:.4g} kg\n",
      result.depth, result.rim_height, result.rim_radius, result.volume, result.ejected_mass);
  for (const auto& b : result.boulders) {
    fmt::print("  boulder {}: displaced by {:.4g} m ({:.4g}, {:.4g}, {:.4g})\n", b.name,
               b.displacement_magnitude, b.displacement[0], b.displacement[1], b.displacement[2]);
  }
  for (const auto& w : result.warnings) fmt::print("  warning: {}\n", w);
  fmt::print("  wrote {} and {}\n", (directory / "crater.json").string(),
             (directory / "crater_profile.csv").string());
}

void add_measure_command(CLI::App& parent) {
  auto options = std::make_shared<MeasureOptions>();
  auto* sub = parent.add_subcommand(
      "measure",
      "Measure the crater of an SPH snapshot (radius at the pre-impact level, depth, rim, profile)");
  sub->add_option("snapshot", options->snapshot, "Snapshot (HDF5) written by craterkit simulate")->required();
  sub->add_option("--rho-initial", options->rho_initial,
                  "Initial bulk density of the target matrix, kg/m^3 (default: snapshot attribute "
                  "initial_bulk_density)");
  sub->add_option("--spacing", options->spacing,
                  "Initial particle spacing, m (default: snapshot attribute particle_spacing; on a graded "
                  "target the local spacing from inner_spacing, inner_radius and grading)");
  sub->add_option("--kernel", options->kernel,
                  "cubic_spline or wendland_c2 (default: snapshot attribute kernel, else cubic_spline)");
  sub->add_option("--centre", options->centre, "Impact point X Y on the pre-impact plane, m (default 0 0)")
      ->expected(2);
  sub->add_option("--max-radius", options->max_radius,
                  "Outer end of the rays, m (default: target extent - 2 h - spacing)");
  sub->add_option("--azimuths", options->azimuths, "Number of rays (multiple of 4; default 64)");
  sub->add_option("--radial-step", options->radial_step, "Radial sample step, m (default (local) spacing/4)");
  sub->add_option("--wall-depth", options->wall_depth,
                  "Depth below z = 0 that marks the crater wall, m (default one (local) spacing)");
  sub->add_flag(
      "--quarter", options->quarter,
      "Quarter-domain run mirrored at x = 0 and y = 0 (default: snapshot attribute symmetry = quarter)");
  sub->add_option(
      "--boulders", options->boulders,
      "JSON file: [{\"name\", \"initial_centre\": [x,y,z], \"material\" | \"ids\" | \"id_range\"}]");
  sub->add_option("--out", options->out,
                  "Directory for crater.json and crater_profile.csv (default: the "
                  "snapshot's directory)");
  sub->add_flag("--json", options->json, "Print crater.json on stdout");
  sub->footer(
      "Method and file formats: docs/crater_measurement.md. Exit status 2 for bad input (the message "
      "names the flag or attribute).");
  sub->callback([options] { run_measure(*options); });
}

const bool registered = register_command({"measure", 60, &add_measure_command});

}  // namespace
}  // namespace craterkit::cli
