// craterkit rates: impactor radius and relative crater-formation rate for each crater diameter and
// cohesion (docs/physics.md sec. 7; chronology/relative_rates.hpp).
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "craterkit/chronology/body.hpp"
#include "craterkit/chronology/law_propagation.hpp"
#include "craterkit/chronology/population.hpp"
#include "craterkit/chronology/production.hpp"
#include "craterkit/chronology/scaled_production.hpp"
#include "craterkit/common/input_error.hpp"
#include "json_output.hpp"
#include "law_uncertainty_flags.hpp"
#include "output_checks.hpp"
#include "production_flags.hpp"
#include "scaling_flags.hpp"

namespace {

namespace ck = craterkit::chronology;
using craterkit::InputError;

struct RatesOptions {
  craterkit::cli::ScalingFlags scaling;
  std::string body = "ryugu";
  std::vector<double> cohesion;
  std::vector<double> diameters;
  std::optional<double> q;
  std::optional<std::string> population;
  craterkit::cli::ProductionFlags production;
  double impactor_density = 2600.0;
  craterkit::cli::LawUncertaintyFlags uncertainty;
  bool json = false;
};

void run_rates(const RatesOptions& o) {
  auto inputs = craterkit::cli::resolve_scaling_flags(o.scaling);
  const ck::Body body = ck::load_body(o.production.body);
  craterkit::cli::check_cohesions(o.cohesion);
  if (o.diameters.empty()) throw InputError("--diameters needs at least one crater diameter (m)");
  for (double d : o.diameters) {
    if (!(d > 0.0) || !std::isfinite(d))
      throw InputError(fmt::format("--diameters {} must be a finite number > 0 m", d));
  }
  if (o.q && o.population)
    throw InputError("--q and --population cannot both be given: choose one impactor population");

  ck::ImpactorPopulation population;
  if (o.q) {
    if (!(*o.q < -1.0))
      throw InputError(fmt::format("--q {} must be < -1 (differential slope of dN/da)", *o.q));
    population = ck::power_law_population(*o.q);
  } else {
    population = ck::load_population(o.population.value_or("main_belt_approx_bottke2005"));
  }
  const auto setup = craterkit::cli::resolve_production_flags(o.production, o.scaling, body, population);
  const auto region = ck::collision_region_from_string(o.production.region);

  craterkit::scaling::Target target;
  target.density = o.scaling.target_density.value_or(body.bulk_density);
  target.gravity = o.scaling.gravity.value_or(body.surface_gravity);
  const double impactor_density = o.scaling.impactor_density.value_or(o.production.impactor_density);
  const double speed = ck::mean_speed(setup.speeds);
  const bool absolute = !o.q.has_value();
  const auto draws = craterkit::cli::draw_laws(inputs, o.uncertainty);

  nlohmann::json rows = nlohmann::json::array();
  for (double D : o.diameters) {
    double first_rate = 0.0;
    for (std::size_t k = 0; k < o.cohesion.size(); ++k) {
      craterkit::scaling::Target reference = target;
      reference.strength = o.cohesion.front();
      target.strength = o.cohesion[k];
      const auto law = ck::scaled_impactor_radius(inputs.law, target, impactor_density);
      const double a = law(ck::apparent_radius_from_rim_diameter(D, setup.diameter), speed);
      const double rate = ck::crater_production_rate(setup, law, D);
      if (k == 0) first_rate = rate;
      // A result that is not a finite number is an error naming its inputs, never a printed "nan".
      if (!std::isfinite(a) || !std::isfinite(rate) || !std::isfinite(rate / first_rate)) {
        throw InputError(fmt::format(
            "--diameters {:g} with --cohesion {:g}: the {} is {} (the inputs overflow or leave the impactor "
            "population's range); give values of physical size",
            D, o.cohesion[k], !std::isfinite(a) ? "impactor radius" : "crater production rate",
            !std::isfinite(a)      ? a
            : !std::isfinite(rate) ? rate
                                   : rate / first_rate));
      }
      nlohmann::json row = {{"crater_diameter", D},
                            {"cohesion", o.cohesion[k]},
                            {"impactor_radius", a},
                            {"relative_rate", rate / first_rate}};
      row["production_rate_per_km2_per_yr"] = absolute ? nlohmann::json(rate * 1e6) : nlohmann::json(nullptr);
      if (draws) {
        const auto spread = ck::rate_spread(setup, draws->laws, target, reference, impactor_density, D);
        row["scaling_law_uncertainty"] = {
            {"impactor_radius", craterkit::cli::percentiles_json(spread.impactor_radius)},
            {"relative_rate", craterkit::cli::percentiles_json(spread.relative_rate)},
            {"production_rate_per_km2_per_yr",
             absolute ? craterkit::cli::percentiles_json(spread.rate, 1e6) : nlohmann::json(nullptr)}};
      }
      rows.push_back(row);
    }
  }

  if (o.json) {
    nlohmann::json out = {{"rows", rows}};
    out["scaling_law"] = craterkit::cli::scaling_law_json(inputs);
    if (draws) {
      out["scaling_law_uncertainty"] = craterkit::cli::law_uncertainty_json(inputs, o.uncertainty, *draws);
    }
    out["conventions"] = {
        {"body", body.name},
        {"region", ck::to_string(region)},
        {"population", population.name},
        {"target_density", target.density},
        {"gravity", target.gravity},
        {"impactor_density", impactor_density},
        {"impact_speed", speed},
        {"speed_distribution_entries", setup.speeds.speed.size()},
        {"rim_to_apparent", setup.diameter.rim_to_apparent},
        {"cross_section", o.production.cross_section},
        {"diameters", "rim-to-rim, m"},
        {"impactor_radius", "m, at the (mean) impact speed"},
        {"relative_rate", "rate of craters larger than the diameter, relative to the first cohesion"}};
    craterkit::cli::print_json(out);
    return;
  }
  std::cout << fmt::format("# craterkit rates: {} ({}), {} collisions, population {}\n", body.name,
                           inputs.law_source, ck::to_string(region), population.name);
  std::cout << fmt::format(
      "# rho = {} kg/m^3, g = {} m/s^2, delta = {} kg/m^3, U = {} m/s, D_rim/D_app = {}\n", target.density,
      target.gravity, impactor_density, speed, setup.diameter.rim_to_apparent);
  if (draws) std::cout << craterkit::cli::law_uncertainty_comment(inputs, o.uncertainty, *draws) << "\n";
  std::cout << fmt::format("{:>16} {:>12} {:>18} {:>16} {:>22}", "crater_diam_m", "cohesion_Pa",
                           "impactor_radius_m", "relative_rate", "rate_per_km2_per_yr");
  if (draws) {
    std::cout << fmt::format(" {:>26} {:>26} {:>26}", "impactor_radius_law_range", "relative_rate_law_range",
                             "rate_law_range");
  }
  std::cout << "\n";
  for (const auto& r : rows) {
    const std::string absolute_rate =
        r["production_rate_per_km2_per_yr"].is_null()
            ? std::string("-")
            : fmt::format("{:.4e}", r["production_rate_per_km2_per_yr"].get<double>());
    std::cout << fmt::format("{:>16.4g} {:>12.4g} {:>18.4e} {:>16.4e} {:>22}",
                             r["crater_diameter"].get<double>(), r["cohesion"].get<double>(),
                             r["impactor_radius"].get<double>(), r["relative_rate"].get<double>(),
                             absolute_rate);
    if (draws) {
      const auto& u = r["scaling_law_uncertainty"];
      const auto range = [](const nlohmann::json& p) {
        return p.is_null() ? std::string("-")
                           : fmt::format("[{:.4e}, {:.4e}]", p["p16"].get<double>(), p["p84"].get<double>());
      };
      std::cout << fmt::format(" {:>26} {:>26} {:>26}", range(u["impactor_radius"]),
                               range(u["relative_rate"]), range(u["production_rate_per_km2_per_yr"]));
    }
    std::cout << "\n";
  }
}

void add_rates_command(CLI::App& parent) {
  auto* sub = parent.add_subcommand("rates",
                                    "Impactor radius and crater-formation rate relative to the first "
                                    "cohesion, per crater diameter and cohesion");
  auto o = std::make_shared<RatesOptions>();
  craterkit::cli::add_scaling_flags(*sub, o->scaling);
  craterkit::cli::add_production_flags(*sub, o->production);
  craterkit::cli::add_law_uncertainty_flags(*sub, o->uncertainty);
  sub->add_option_function<std::vector<std::string>>(
         "--cohesion",
         [o](const std::vector<std::string>& items) {
           o->cohesion = craterkit::cli::number_list("--cohesion", items);
         },
         "Cohesions Y of the scaling law, Pa (comma-separated); rates are relative to the first")

      ->required();
  sub->add_option_function<std::vector<std::string>>(
         "--diameters",
         [o](const std::vector<std::string>& items) {
           o->diameters = craterkit::cli::number_list("--diameters", items);
         },
         "Rim-to-rim crater diameters, m (comma-separated)")

      ->required();
  sub->add_option("--q", o->q, "Single power-law impactor population dN/da ~ a^q (relative rates only)");
  sub->add_option(
      "--population", o->population,
      "Impactor population in data/populations/ or a .toml file (default main_belt_approx_bottke2005)");
  sub->add_flag("--json", o->json, "Print JSON {\"rows\": [...]} instead of a table");
  sub->footer(
      "Target density and gravity default to the body's; --impactor-density defaults to 2600 kg/m^3 and the "
      "impact speed to the body's mean speed for --region. The impactor radius is given at the (mean) "
      "speed. With --fit, the fit's covariance is carried into every column by --samples draws of the "
      "fitted constants (the *_law_range columns and scaling_law_uncertainty in JSON: 15.87-84.13 %).");
  sub->callback([o] { run_rates(*o); });
}

const bool rates_registered = craterkit::cli::register_command({"rates", 30, &add_rates_command});

}  // namespace
