// craterkit run: the main job on its embedded default. For now (scaling stage only):
//  1. the SCI impact on Ryugu through the Jutzi et al. (2022) constants at a few cohesions, against the
//     observed apparent radius 7.25 +- 0.8 m (Arakawa et al. 2020);
//  2. the Ceres fit of the shipped example table data/examples/radii_example.csv (synthetic, see its header).
// Later stages (simulation, sweep, chronology) are meant to slot into run_main_job as further steps.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "craterkit/common/atomic_file.hpp"
#include "craterkit/common/data_path.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/constant_sets.hpp"
#include "craterkit/scaling/fit.hpp"
#include "craterkit/scaling/fit_json.hpp"
#include "craterkit/scaling/radii_table.hpp"
#include "fit_report.hpp"
#include "json_output.hpp"

namespace craterkit::cli {
namespace {

struct RunOptions {
  std::optional<std::string> out;
  bool json = false;
};

// The SCI experiment (docs/physics.md sections 4 and 6): 2 kg, 2700 kg/m^3, 2 km/s, vertical, into Ryugu.
constexpr double kSciMass = 2.0;                             // kg
constexpr double kSciDensity = 2700.0;                       // kg/m^3
constexpr double kSciVelocity = 2000.0;                      // m/s
constexpr double kRyuguGravity = 1.4e-4;                     // m/s^2
constexpr double kSciObservedRadius = 7.25;                  // m, apparent radius (Arakawa et al. 2020)
constexpr double kSciObservedSigma = 0.8;                    // m
const std::vector<double> kCohesions{0.05, 0.5, 5.0, 50.0};  // Pa

nlohmann::json sci_example(bool print) {
  const auto set = scaling::load_constant_set("jutzi2022_ryugu");
  scaling::Impactor impactor{std::cbrt(3.0 * kSciMass / (4.0 * std::numbers::pi * kSciDensity)), kSciDensity,
                             kSciVelocity};
  scaling::Target target{set.target_density.value(), kRyuguGravity, set.strength.value()};
  nlohmann::json rows = nlohmann::json::array();
  if (print) {
    fmt::print(
        "SCI impact on Ryugu: {} kg, a = {:.4f} m, {} kg/m^3, U = {} m/s into rho = {} kg/m^3, g = {} "
        "m/s^2\n",
        kSciMass, impactor.radius, kSciDensity, kSciVelocity, target.density, target.gravity);
    fmt::print("law: {} ({} form: {} = {}, {} = {}, mu = {}, nu = {})\n", set.name,
               scaling::to_string(set.law.form), scaling::coefficient_name(set.law.form, 1),
               set.law.coefficient_1, scaling::coefficient_name(set.law.form, 2), set.law.coefficient_2,
               set.law.mu, set.law.nu);
    fmt::print("observed apparent radius: {} +- {} m (Arakawa et al. 2020)\n", kSciObservedRadius,
               kSciObservedSigma);
    fmt::print("  {:>9}  {:>9}  {:>7}  {:>12}  {:>9}  {}\n", "Y (Pa)", "R (m)", "R/a", "regime", "gravity %",
               "vs observed");
  }
  std::vector<double> cohesions{*set.strength};
  for (double y : kCohesions) {
    if (y != *set.strength) cohesions.push_back(y);
  }
  for (double y : cohesions) {
    target.strength = y;
    const double radius = scaling::crater_radius(set.law, impactor, target);
    const auto regime = scaling::regime(set.law, impactor, target);
    const double pull = (radius - kSciObservedRadius) / kSciObservedSigma;
    rows.push_back({{"strength", y},
                    {"crater_radius", radius},
                    {"radius_ratio", radius / impactor.radius},
                    {"regime", scaling::to_string(regime.kind)},
                    {"gravity_share", regime.gravity_share},
                    {"deviation_sigma", pull}});
    if (print) {
      fmt::print("  {:>9.3g}  {:>9.3f}  {:>7.1f}  {:>12}  {:>9.1f}  {:+.1f} sigma{}\n", y, radius,
                 radius / impactor.radius, scaling::to_string(regime.kind), 100.0 * regime.gravity_share,
                 pull, y == *set.strength ? "  (the set's cohesion)" : "");
    }
  }
  target.strength = 0.0;
  const double gravity_limit = scaling::crater_radius(set.law, impactor, target);
  target.strength = *set.strength;
  const double impactor_for_observed =
      scaling::solve_impactor_radius(set.law, kSciObservedRadius, impactor, target);
  if (print) {
    fmt::print("  cohesionless (pure-gravity) limit: R = {:.3f} m\n", gravity_limit);
    fmt::print("  impactor radius that makes R = {} m at Y = {} Pa: {:.4f} m\n\n", kSciObservedRadius,
               *set.strength, impactor_for_observed);
  }
  return {{"impactor_radius", impactor.radius},
          {"impactor_mass", kSciMass},
          {"impactor_density", kSciDensity},
          {"velocity", kSciVelocity},
          {"target_density", set.target_density.value()},
          {"gravity", kRyuguGravity},
          {"constant_set", set.name},
          {"observed_crater_radius", kSciObservedRadius},
          {"observed_crater_radius_sigma", kSciObservedSigma},
          {"cohesions", rows},
          {"gravity_limit_radius", gravity_limit},
          {"impactor_radius_for_observed", impactor_for_observed}};
}

nlohmann::json example_fit(bool print) {
  const auto path = data_file("examples/radii_example.csv");
  const auto table = scaling::read_radii_csv(path);
  scaling::FitOptions options;
  options.form = scaling::Form::hh2011;  // the form the synthetic table was generated in
  const auto fit = scaling::fit_scaling_law(table, options);
  if (print) {
    print_fit_report(fit, path.string(), table.rows.size());
    fmt::print(
        "  (synthetic table: generated by scripts/make_radii_example.py with H1 = 0.60, H2 = 0.25, "
        "mu = 0.44, nu = 0.4 and 5 % noise)\n");
  }
  return scaling::fit_to_json(fit);
}

void run_main_job(const RunOptions& options) {
  if (options.out && std::filesystem::exists(*options.out) && !std::filesystem::is_directory(*options.out)) {
    throw InputError("--out " + *options.out + " is not allowed: it exists and is not a directory");
  }
  const bool print = !options.json;
  const nlohmann::json sci = sci_example(print);
  const nlohmann::json fit = example_fit(print);
  if (options.out) {
    const std::filesystem::path dir(*options.out);
    std::filesystem::create_directories(dir);
    write_text_atomically(dir / "sci_example.json", sci.dump(2) + "\n");
    write_text_atomically(dir / "scaling_fit.json", fit.dump(2) + "\n");
    if (print)
      fmt::print("written: {}, {}\n", (dir / "sci_example.json").string(),
                 (dir / "scaling_fit.json").string());
  }
  if (options.json) craterkit::cli::print_json(nlohmann::json{{"sci_example", sci}, {"scaling_fit", fit}});
}

void add_run_command(CLI::App& parent) {
  auto options = std::make_shared<RunOptions>();
  auto* sub = parent.add_subcommand(
      "run",
      "The main job on its embedded default: SCI-on-Ryugu scaling example and the fit of the shipped "
      "example radii table");
  sub->add_option("--out", options->out,
                  "Directory for sci_example.json and scaling_fit.json (atomic writes)");
  sub->add_flag("--json", options->json, "Print one JSON object instead of text");
  sub->callback([options] { run_main_job(*options); });
}

const bool registered = register_command({"run", 5, &add_run_command});

}  // namespace
}  // namespace craterkit::cli
