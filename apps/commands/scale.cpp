// craterkit scale: the point-source crater radius of one impact, or the impactor radius that makes a
// given crater (docs/physics.md section 6).
#include <cmath>
#include <iostream>
#include <memory>
#include <numbers>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "craterkit/chronology/body.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/point_source.hpp"
#include "json_output.hpp"
#include "scaling_flags.hpp"

namespace craterkit::cli {
namespace {

struct ScaleOptions {
  ScalingFlags scaling;
  std::optional<double> impactor_radius;
  std::optional<double> crater_radius;
  std::optional<std::string> body;  // --body NAME|FILE: gravity (and target density) of a shipped body
  bool json = false;
};

void run_scale(const ScaleOptions& options) {
  ScalingInputs inputs = resolve_scaling_flags(options.scaling);
  std::optional<chronology::Body> body;
  if (options.body) {
    body = chronology::load_body(*options.body);
    // As in `rates` and `age`: the body's gravity and bulk density unless --gravity / --target-density are
    // given (the body's density replaces a constant set's).
    if (!options.scaling.gravity) inputs.gravity = body->surface_gravity;
    if (!options.scaling.target_density) inputs.target_density = body->bulk_density;
  }
  if (options.impactor_radius.has_value() == options.crater_radius.has_value()) {
    throw InputError(
        "give exactly one of --impactor-radius (to compute the crater radius) or --crater-radius "
        "(to solve for the impactor radius)");
  }
  const double given = options.impactor_radius ? *options.impactor_radius : *options.crater_radius;
  const char* given_flag = options.impactor_radius ? "--impactor-radius" : "--crater-radius";
  if (!(given > 0.0) || !std::isfinite(given)) {
    throw InputError(fmt::format("{} {} is not allowed: must be a finite number > 0 (m)", given_flag, given));
  }
  scaling::Impactor impactor{0.0, require_value(inputs.impactor_density, "--impactor-density"),
                             require_value(inputs.velocity, "--velocity")};
  const scaling::Target target{require_value(inputs.target_density, "--target-density"),
                               require_value(inputs.gravity, "--gravity"),
                               require_value(inputs.strength, "--strength")};
  double crater_radius = 0.0;
  if (options.impactor_radius) {
    impactor.radius = *options.impactor_radius;
    crater_radius = scaling::crater_radius(inputs.law, impactor, target);
  } else {
    crater_radius = *options.crater_radius;
    impactor.radius = scaling::solve_impactor_radius(inputs.law, crater_radius, impactor, target);
  }
  const auto pi = scaling::pi_groups(impactor, target);
  const auto regime = scaling::regime(inputs.law, impactor, target);
  const double pi_r = crater_radius * std::cbrt(target.density / scaling::impactor_mass(impactor));
  // Values so large or small that the arithmetic overflows give inf or NaN: an error, never a printed
  // result.
  for (const auto& [name, value] :
       {std::pair{"crater radius", crater_radius}, std::pair{"impactor radius", impactor.radius},
        std::pair{"impactor mass", scaling::impactor_mass(impactor)}, std::pair{"pi_R", pi_r},
        std::pair{"pi_2", pi.pi2}, std::pair{"pi_3", pi.pi3}, std::pair{"pi_4", pi.pi4}}) {
    if (!std::isfinite(value)) {
      throw InputError(fmt::format(
          "{} {:g}, --impactor-density {:g}, --velocity {:g}, --target-density {:g}, --gravity {:g}, "
          "--strength {:g}: the {} is {} (the numbers overflow); give values of physical size",
          given_flag, given, impactor.density, impactor.velocity, target.density, target.gravity,
          target.strength, name, value));
    }
  }
  std::optional<double> gravity_limit;
  std::optional<double> strength_limit;
  if (target.gravity > 0.0 &&
      (inputs.law.form == scaling::Form::holsapple || !std::isnan(inputs.law.coefficient_1))) {
    gravity_limit = scaling::gravity_limit_radius(inputs.law, impactor, target);
  }
  if (target.strength > 0.0) strength_limit = scaling::strength_limit_radius(inputs.law, impactor, target);

  if (options.json) {
    const auto optional_json = [](const std::optional<double>& v) {
      return v ? nlohmann::json(*v) : nlohmann::json(nullptr);
    };
    nlohmann::json out{
        {"crater_radius", crater_radius},
        {"impactor_radius", impactor.radius},
        {"solved_for", options.crater_radius ? "impactor_radius" : "crater_radius"},
        {"impactor_mass", scaling::impactor_mass(impactor)},
        {"impactor_density", impactor.density},
        {"velocity", impactor.velocity},
        {"target_density", target.density},
        {"gravity", target.gravity},
        {"strength", target.strength},
        {"pi_R", pi_r},
        {"pi_2", pi.pi2},
        {"pi_3", pi.pi3},
        {"pi_4", pi.pi4},
        {"radius_ratio", crater_radius / impactor.radius},
        {"regime", scaling::to_string(regime.kind)},
        {"gravity_share", regime.gravity_share},
        {"strength_share", regime.strength_share},
        {"gravity_limit_radius", optional_json(gravity_limit)},
        {"strength_limit_radius", optional_json(strength_limit)},
        {"scaling_law", scaling_law_json(inputs)},
    };
    out["body"] = body ? nlohmann::json(body->name) : nlohmann::json(nullptr);
    craterkit::cli::print_json(out);
    return;
  }
  if (options.crater_radius) {
    fmt::print("impactor radius: {:.6g} m (mass {:.6g} kg) makes a crater of radius {:.6g} m\n",
               impactor.radius, scaling::impactor_mass(impactor), crater_radius);
  } else {
    fmt::print("crater radius: {:.6g} m\n", crater_radius);
  }
  fmt::print("  R/a = {:.6g}, pi_R = {:.6g}, pi_2 = {:.6g}, pi_3 = {:.6g}, pi_4 = {:.6g}\n",
             crater_radius / impactor.radius, pi_r, pi.pi2, pi.pi3, pi.pi4);
  fmt::print("  regime: {} (gravity term {:.1f} %, strength term {:.1f} %)\n",
             scaling::to_string(regime.kind), 100.0 * regime.gravity_share, 100.0 * regime.strength_share);
  if (gravity_limit) fmt::print("  pure-gravity limit: {:.6g} m\n", *gravity_limit);
  if (strength_limit) fmt::print("  pure-strength limit: {:.6g} m\n", *strength_limit);
  fmt::print("  law: {} form from {}\n", scaling::to_string(inputs.law.form), inputs.law_source);
  if (body) {
    fmt::print("  target: {} (g = {:.6g} m/s^2, rho = {:.6g} kg/m^3)\n", body->name, target.gravity,
               target.density);
  }
}

void add_scale_command(CLI::App& parent) {
  auto options = std::make_shared<ScaleOptions>();
  auto* sub = parent.add_subcommand("scale",
                                    "Point-source crater scaling (Holsapple 1993; Housen & Holsapple 2011): "
                                    "crater radius of an impact, or the "
                                    "impactor radius for a given crater radius (--crater-radius)");
  auto* impactor = sub->add_option("--impactor-radius", options->impactor_radius, "Impactor radius a, m");
  auto* crater = sub->add_option("--crater-radius", options->crater_radius,
                                 "Apparent crater radius R, m: solve for the impactor radius instead");
  impactor->excludes(crater);
  add_scaling_flags(*sub, options->scaling);
  add_strength_flag(*sub, options->scaling);
  sub->add_option(
      "--body", options->body,
      "Target body (data/bodies/NAME.toml, e.g. ryugu, or a body file): its surface gravity and bulk "
      "density, as in rates and age (--gravity and --target-density override them)");
  sub->add_flag("--json", options->json, "Print a JSON object instead of text");
  sub->footer(
      "The law comes from --params NAME (data/scaling/NAME.toml), --fit FIT.json, or --K1 --K2 (Holsapple "
      "form) "
      "/ --H1 --H2 (Housen & Holsapple 2011 form) with --mu --nu; explicit flags override a set or fit. "
      "Strength and target density default to the set's values; --body gives the gravity and the target "
      "density (as in rates and age). SI units throughout.");
  sub->callback([options] { run_scale(*options); });
}

const bool scale_registered = register_command({"scale", 10, &add_scale_command});

}  // namespace
}  // namespace craterkit::cli
