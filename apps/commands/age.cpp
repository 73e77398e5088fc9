// craterkit age: model (crater-retention) ages of a counted surface unit per cohesion, by the Poisson
// likelihood of Michael et al. (2016), with the classical cumulative fit for comparison
// (docs/physics.md sec. 7; chronology/model_age.hpp). --plot draws the standard figure through
// scripts/plot_age.py.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "craterkit/chronology/body.hpp"
#include "craterkit/chronology/chronology_system.hpp"
#include "craterkit/chronology/crater_counts.hpp"
#include "craterkit/chronology/law_propagation.hpp"
#include "craterkit/chronology/model_age.hpp"
#include "craterkit/chronology/population.hpp"
#include "craterkit/chronology/production.hpp"
#include "craterkit/chronology/scaled_production.hpp"
#include "craterkit/common/atomic_file.hpp"
#include "craterkit/common/data_path.hpp"
#include "craterkit/common/input_error.hpp"
#include "json_output.hpp"
#include "law_uncertainty_flags.hpp"
#include "output_checks.hpp"
#include "production_flags.hpp"
#include "python_plot.hpp"
#include "scaling_flags.hpp"

namespace {

namespace ck = craterkit::chronology;
using craterkit::InputError;

struct AgeOptions {
  craterkit::cli::ScalingFlags scaling;
  std::string counts;
  std::vector<double> cohesion;
  std::string population = "main_belt_approx_bottke2005";
  craterkit::cli::ProductionFlags production;
  std::optional<double> min_diameter;
  std::optional<double> max_diameter;
  std::optional<double> equilibrium;
  std::string fractions = "weight";  // --fractions weight|whole
  // --chronology NAME|FILE: a published chronology system instead of the scaling law.
  std::optional<std::string> chronology;
  std::optional<std::string> plot;
  std::string presentation = "cumulative";  // --presentation cumulative|differential|R (the figure)
  std::string prior = "age";                // --prior age|density (with --chronology)
  craterkit::cli::LawUncertaintyFlags uncertainty;
  bool json = false;
};

std::vector<double> downsample(const std::vector<double>& v, std::size_t n) {
  if (v.size() <= n) return v;
  std::vector<double> out;
  for (std::size_t i = 0; i < n; ++i) out.push_back(v[i * (v.size() - 1) / (n - 1)]);
  return out;
}

// Observed cumulative SFD (diameter in m, craters per km^2) for the figure: at every crater, largest first,
// or at every bin.
nlohmann::json observed_cumulative(const ck::CraterCounts& counts) {
  nlohmann::json observed = nlohmann::json::array();
  if (counts.binned()) {
    for (const auto& b : counts.bins)
      observed.push_back({b.diameter, b.cumulative_count / counts.area * 1e6});
    return observed;
  }
  std::vector<std::pair<double, double>> sorted;
  for (std::size_t i = 0; i < counts.diameters.size(); ++i)
    sorted.emplace_back(counts.diameters[i], counts.fractions[i]);
  std::sort(sorted.begin(), sorted.end(), [](auto a, auto b) { return a.first > b.first; });
  double running = 0.0;
  for (const auto& [d, f] : sorted) {
    running += f;
    observed.push_back({d, running / counts.area * 1e6});
  }
  return observed;
}

std::pair<double, double> observed_range(const nlohmann::json& observed) {
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  for (const auto& p : observed) {
    lo = std::min(lo, p[0].get<double>());
    hi = std::max(hi, p[0].get<double>());
  }
  return {lo, hi};
}

// Writes the figure of `out` (the JSON of the ages) through plot_age.py.
void draw_figure(const nlohmann::json& out, const AgeOptions& o, const std::filesystem::path& script) {
  // The data file is written atomically beside the figure; the script writes the figure atomically too.
  const std::filesystem::path figure(*o.plot);
  const auto data_path = craterkit::temporary_sibling(figure).string() + ".json";
  craterkit::write_text_atomically(data_path, out.dump());
  const int status =
      craterkit::cli::run_python({script.string(), data_path, figure.string(), o.presentation});
  std::error_code ignored;
  std::filesystem::remove(data_path, ignored);
  if (status != 0)
    throw std::runtime_error(fmt::format("plot_age.py failed (exit status {}); no figure written", status));
}

// The fit range and conventions shared by both kinds of production.
ck::AgeFitOptions fit_options(const AgeOptions& o) {
  ck::AgeFitOptions fit;
  if (o.min_diameter) {
    if (!(*o.min_diameter > 0.0))
      throw InputError(fmt::format("--min-diameter {} must be > 0 m", *o.min_diameter));
    fit.min_diameter = *o.min_diameter;
  }
  if (o.max_diameter) fit.max_diameter = *o.max_diameter;
  fit.weight_by_fraction = o.fractions == "weight";
  if (o.equilibrium) {
    fit.cap.enabled = true;
    fit.cap.fraction_of_geometric = *o.equilibrium;
    ck::validate(fit.cap);
  }
  return fit;
}

// --chronology: one age from a published chronology system (production polynomial and N(1)(t)), the way
// crater-counting tools date a count; the scaling law, cohesion and body play no part.
void run_age_chronology(const AgeOptions& o, const std::filesystem::path& script) {
  const auto& s = o.scaling;
  const bool law_flags = s.params || s.fit_file || s.group || s.K1 || s.K2 || s.H1 || s.H2 || s.mu || s.nu ||
                         s.gravity || s.target_density || s.impactor_density || s.velocity || s.strength;
  if (law_flags || !o.cohesion.empty()) {
    throw InputError("--chronology " + *o.chronology +
                     " dates the count with that system's production and chronology functions: it takes no "
                     "scaling-law flag (--params, --fit, --K1 ..., --velocity, ...) and no --cohesion");
  }
  const auto system = ck::load_chronology_system(*o.chronology);
  const ck::CraterCounts counts = ck::read_crater_counts(o.counts);
  ck::AgeFitOptions fit = fit_options(o);
  fit.clock = ck::chronology_clock(system);
  fit.prior_uniform_in_density = o.prior == "density";
  const auto est = ck::fit_model_age(counts, ck::chronology_production(system), fit);
  nlohmann::json age = {{"chronology", system.name},
                        {"median_yr", est.median},
                        {"mode_yr", est.mode},
                        {"sigma1_yr", {est.sigma1_low, est.sigma1_high}},
                        {"sigma2_yr", {est.sigma2_low, est.sigma2_high}},
                        {"reaches_max_age", est.reaches_max_age},
                        {"cumulative_fit_age_yr", est.cumulative_fit_age},
                        {"cumulative_fit_sigma_yr", est.cumulative_fit_sigma},
                        {"craters_in_range", est.craters_in_range},
                        {"fit_min_diameter", est.min_diameter},
                        {"fit_max_diameter", std::isinf(est.max_diameter) ? nlohmann::json(nullptr)
                                                                          : nlohmann::json(est.max_diameter)},
                        {"n1_at_median_per_km2", ck::n1(system, est.median)},
                        {"label", system.title}};
  nlohmann::json out;
  out["counts"] = {{"source", counts.source},
                   {"area_km2", counts.area * 1e-6},
                   {"binned", counts.binned()},
                   {"buffered", counts.buffered}};
  if (o.plot) {
    // The figure's data: the counts, the isochron at the median age (inside the polynomial's range) and the
    // age density, as for the scaling law's ages.
    nlohmann::json figure = out;
    figure["observed_cumulative_per_km2"] = observed_cumulative(counts);
    const auto [d_lo, d_hi] = observed_range(figure["observed_cumulative_per_km2"]);
    const double lo = std::max(0.7 * std::min(d_lo, est.min_diameter), system.min_diameter);
    const double hi = std::min(1.5 * std::max(d_hi, est.min_diameter), system.max_diameter);
    const auto production = ck::chronology_production(system);
    nlohmann::json isochron = nlohmann::json::array();
    for (int i = 0; i <= 60; ++i) {
      const double d = lo * std::pow(hi / lo, i / 60.0);
      isochron.push_back(
          {d, ck::expected_cumulative_density(fit.cap, d, fit.clock(est.median), production(d)) * 1e6});
    }
    nlohmann::json plotted = age;
    plotted["isochron"] = isochron;
    plotted["age_grid_yr"] = downsample(est.age_grid, 400);
    plotted["density_per_yr"] = downsample(est.density, 400);
    figure["ages"] = nlohmann::json::array({plotted});
    figure["conventions"] = {{"body", system.body}};
    figure["title"] = "Poisson likelihood age (" + system.title + ")";
    draw_figure(figure, o, script);
  }
  if (o.json) {
    out["chronology_system"] = {
        {"name", system.name}, {"title", system.title}, {"body", system.body}, {"citation", system.citation}};
    out["conventions"] = {
        {"fractions", o.fractions},
        {"equilibrium_fraction",
         fit.cap.enabled ? nlohmann::json(fit.cap.fraction_of_geometric) : nlohmann::json(nullptr)},
        {"prior", fmt::format("uniform in {} on [0, {:g}] yr",
                              o.prior == "density" ? "crater density" : "age", fit.max_age)}};
    out["ages"] = nlohmann::json::array({age});
    craterkit::cli::print_json(out);
    return;
  }
  std::cout << fmt::format("# craterkit age: {} ({:.4g} km^2), chronology system {} ({})\n", counts.source,
                           counts.area * 1e-6, system.title, system.name);
  std::cout << fmt::format("{:>8} {:>12} {:>25} {:>25} {:>20}\n", "N_fit", "median_Myr", "1-sigma_Myr",
                           "2-sigma_Myr", "cumulative_fit_Myr");
  std::cout << fmt::format(
      "{:>8.4g} {:>12.4g} {:>25} {:>25} {:>20}{}\n", est.craters_in_range, est.median / 1e6,
      fmt::format("[{:.4g}, {:.4g}]", est.sigma1_low / 1e6, est.sigma1_high / 1e6),
      fmt::format("[{:.4g}, {:.4g}]", est.sigma2_low / 1e6, est.sigma2_high / 1e6),
      fmt::format("{:.4g} +- {:.2g}", est.cumulative_fit_age / 1e6, est.cumulative_fit_sigma / 1e6),
      est.reaches_max_age ? "  (density reaches the maximum age: a lower bound)" : "");
}

void run_age(const AgeOptions& o) {
  std::filesystem::path script;
  if (o.plot) {
    const auto ext = std::filesystem::path(*o.plot).extension();
    if (ext != ".png" && ext != ".pdf" && ext != ".svg") {
      throw InputError("--plot " + *o.plot + ": the figure's extension must be .png, .pdf or .svg");
    }
    const auto dir = std::filesystem::absolute(*o.plot).parent_path();
    if (!std::filesystem::is_directory(dir)) {
      throw InputError("--plot " + *o.plot + ": directory " + dir.string() + " does not exist");
    }
    script = craterkit::cli::plot_script("plot_age.py", "CRATERKIT_PLOT_AGE_SCRIPT");
    if (const auto why = craterkit::cli::plotting_unavailable(script, "CRATERKIT_PLOT_AGE_SCRIPT");
        !why.empty())
      throw std::runtime_error("--plot: " + why + "; no figure written");
  }
  if (o.chronology) {
    run_age_chronology(o, script);
    return;
  }
  if (o.prior != "age") {
    throw InputError("--prior " + o.prior +
                     " needs --chronology: with the scaling law's constant flux both priors are the same");
  }
  auto inputs = craterkit::cli::resolve_scaling_flags(o.scaling);
  const ck::Body body = ck::load_body(o.production.body);
  craterkit::cli::check_cohesions(o.cohesion);
  const ck::CraterCounts counts = ck::read_crater_counts(o.counts);
  // A crater wider than the body, or a counting area larger than its surface, is a unit or file mix-up.
  const double body_diameter = 2.0 * body.mean_radius;
  auto check_diameter = [&](double d) {
    if (body_diameter > 0.0 && d > body_diameter) {
      throw InputError(
          fmt::format("{}: a crater of diameter {:g} m is larger than {} ({:g} m across); are the "
                      "diameters in the file's units (km in .scc/.diam)?",
                      o.counts, d, body.name, body_diameter));
    }
  };
  for (const double d : counts.diameters) check_diameter(d);
  for (const auto& bin : counts.bins) check_diameter(bin.diameter);
  if (body.surface_area > 0.0 && counts.area > 1.05 * body.surface_area) {
    throw InputError(fmt::format("{}: the counting area {:g} m^2 is larger than the surface of {} ({:g} m^2)",
                                 o.counts, counts.area, body.name, body.surface_area));
  }

  const auto setup = craterkit::cli::resolve_production_flags(o.production, o.scaling, body,
                                                              ck::load_population(o.population));
  const auto region = ck::collision_region_from_string(o.production.region);

  const ck::AgeFitOptions fit = fit_options(o);

  craterkit::scaling::Target target;
  target.density = o.scaling.target_density.value_or(body.bulk_density);
  target.gravity = o.scaling.gravity.value_or(body.surface_gravity);
  const double impactor_density = o.scaling.impactor_density.value_or(o.production.impactor_density);
  const auto draws = craterkit::cli::draw_laws(inputs, o.uncertainty);

  const nlohmann::json observed = observed_cumulative(counts);
  const auto [d_lo, d_hi] = observed_range(observed);

  nlohmann::json ages = nlohmann::json::array();
  for (double y : o.cohesion) {
    target.strength = y;
    const auto production =
        ck::production_function(setup, ck::scaled_impactor_radius(inputs.law, target, impactor_density));
    const auto est = ck::fit_model_age(counts, production, fit);
    // Isochron at the median age over the plotted diameters.
    nlohmann::json isochron = nlohmann::json::array();
    const double lo = 0.7 * std::min(d_lo, est.min_diameter), hi = 1.5 * std::max(d_hi, est.min_diameter);
    for (int i = 0; i <= 60; ++i) {
      const double d = lo * std::pow(hi / lo, i / 60.0);
      isochron.push_back({d, ck::expected_cumulative_density(fit.cap, d, est.median, production(d)) * 1e6});
    }
    ages.push_back({{"cohesion", y},
                    {"median_yr", est.median},
                    {"mode_yr", est.mode},
                    {"sigma1_yr", {est.sigma1_low, est.sigma1_high}},
                    {"sigma2_yr", {est.sigma2_low, est.sigma2_high}},
                    {"reaches_max_age", est.reaches_max_age},
                    {"cumulative_fit_age_yr", est.cumulative_fit_age},
                    {"cumulative_fit_sigma_yr", est.cumulative_fit_sigma},
                    {"craters_in_range", est.craters_in_range},
                    {"fit_min_diameter", est.min_diameter},
                    {"fit_max_diameter", std::isinf(est.max_diameter) ? nlohmann::json(nullptr)
                                                                      : nlohmann::json(est.max_diameter)},
                    {"production_rate_at_min_diameter_per_km2_per_yr", production(est.min_diameter) * 1e6},
                    {"isochron", isochron},
                    {"age_grid_yr", downsample(est.age_grid, 400)},
                    {"density_per_yr", downsample(est.density, 400)}});
    if (draws) {
      const auto spread = ck::model_age_spread(counts, setup, draws->laws, target, impactor_density, fit);
      ages.back()["scaling_law_uncertainty"] = {
          {"median_yr", craterkit::cli::percentiles_json(spread.median)}};
      ages.back()["total_uncertainty"] = {{"median_yr", spread.total_median},
                                          {"sigma1_yr", {spread.total_sigma1_low, spread.total_sigma1_high}},
                                          {"sigma2_yr", {spread.total_sigma2_low, spread.total_sigma2_high}}};
    }
  }

  nlohmann::json out;
  out["counts"] = {{"source", counts.source},
                   {"area_km2", counts.area * 1e-6},
                   {"binned", counts.binned()},
                   {"craters", counts.binned() ? counts.bins.front().cumulative_count
                                               : static_cast<double>(counts.diameters.size())}};
  out["scaling_law"] = craterkit::cli::scaling_law_json(inputs);
  if (draws) {
    auto description = craterkit::cli::law_uncertainty_json(inputs, o.uncertainty, *draws);
    description["reported"] = {
        {"counting",
         "median_yr, sigma1_yr, sigma2_yr: the Poisson likelihood of the counts with the fitted "
         "(central) constants"},
        {"scaling_law", "scaling_law_uncertainty.median_yr: percentiles of the median age over the draws"},
        {"total", "total_uncertainty: the age density averaged over the draws (counting and law together)"}};
    out["scaling_law_uncertainty"] = description;
  }
  out["conventions"] = {
      {"body", body.name},
      {"region", ck::to_string(region)},
      {"population", setup.population.name},
      {"target_density", target.density},
      {"gravity", target.gravity},
      {"impactor_density", impactor_density},
      {"impact_speed", ck::mean_speed(setup.speeds)},
      {"rim_to_apparent", setup.diameter.rim_to_apparent},
      {"cross_section", o.production.cross_section},
      {"equilibrium_fraction",
       fit.cap.enabled ? nlohmann::json(fit.cap.fraction_of_geometric) : nlohmann::json(nullptr)},
      {"fractions", o.fractions},
      {"prior", fmt::format("uniform in age on [0, {:g}] yr", fit.max_age)}};
  nlohmann::json warnings = nlohmann::json::array();
  if (setup.population.approximate) {
    warnings.push_back(fmt::format(
        "population {} is an approximation, not published values (see its notes): absolute ages are "
        "indicative only; the ratios between cohesions are not affected",
        setup.population.name));
  }
  for (const auto& w : warnings) std::cerr << "craterkit: warning: " << w.get<std::string>() << "\n";
  out["warnings"] = warnings;
  out["observed_cumulative_per_km2"] = observed;
  out["ages"] = ages;

  if (o.plot) draw_figure(out, o, script);

  if (o.json) {
    for (auto& a : out["ages"]) {
      a.erase("isochron");  // figure data stays out of the printed JSON unless asked for
    }
    craterkit::cli::print_json(out);
    return;
  }
  std::cout << fmt::format(
      "# craterkit age: {} ({} craters{}, {:.4g} km^2), body {} ({}), law {}, population {}\n", counts.source,
      out["counts"]["craters"].get<double>(), counts.binned() ? " binned" : "", counts.area * 1e-6, body.name,
      ck::to_string(region), inputs.law_source, setup.population.name);
  std::cout << "# Poisson-likelihood age (Michael et al. 2016): median and 1-/2-sigma bounds; classical "
               "cumulative fit\n";
  if (draws) {
    std::cout << craterkit::cli::law_uncertainty_comment(inputs, o.uncertainty, *draws) << "\n";
    std::cout
        << "# counting: Poisson likelihood at the fitted constants; law: 15.87-84.13 % of the median age "
           "over the draws; total: both (the age density averaged over the draws)\n";
  }
  const auto range = [](const nlohmann::json& pair) {
    return fmt::format("[{:.4g}, {:.4g}]", pair[0].get<double>() / 1e6, pair[1].get<double>() / 1e6);
  };
  std::cout << fmt::format("{:>12} {:>8} {:>12} {:>25} {:>25}", "cohesion_Pa", "N_fit", "median_Myr",
                           draws ? "counting_1-sigma_Myr" : "1-sigma_Myr",
                           draws ? "counting_2-sigma_Myr" : "2-sigma_Myr");
  if (draws) std::cout << fmt::format(" {:>25} {:>25}", "law_1-sigma_Myr", "total_1-sigma_Myr");
  std::cout << fmt::format(" {:>20}\n", "cumulative_fit_Myr");
  for (const auto& a : out["ages"]) {
    std::cout << fmt::format("{:>12.4g} {:>8.4g} {:>12.4g} {:>25} {:>25}", a["cohesion"].get<double>(),
                             a["craters_in_range"].get<double>(), a["median_yr"].get<double>() / 1e6,
                             range(a["sigma1_yr"]), range(a["sigma2_yr"]));
    if (draws) {
      const auto& law = a["scaling_law_uncertainty"]["median_yr"];
      std::cout << fmt::format(" {:>25} {:>25}", range(nlohmann::json{law["p16"], law["p84"]}),
                               range(a["total_uncertainty"]["sigma1_yr"]));
    }
    std::cout << fmt::format(
        " {:>20}{}\n",
        fmt::format("{:.4g} +- {:.2g}", a["cumulative_fit_age_yr"].get<double>() / 1e6,
                    a["cumulative_fit_sigma_yr"].get<double>() / 1e6),
        a["reaches_max_age"].get<bool>() ? "  (density reaches the maximum age: a lower bound)" : "");
  }
  if (o.plot) std::cout << "# figure: " << *o.plot << "\n";
}

void add_age_command(CLI::App& parent) {
  auto* sub = parent.add_subcommand("age", "Model ages of a crater-counted surface unit, one per cohesion");
  auto o = std::make_shared<AgeOptions>();
  sub->add_option("COUNTS", o->counts,
                  "Crater counts: .csv (diameters or binned cumulative), craterstats .diam, CraterTools .scc")
      ->required();
  craterkit::cli::add_scaling_flags(*sub, o->scaling);
  craterkit::cli::add_production_flags(*sub, o->production);
  craterkit::cli::add_law_uncertainty_flags(*sub, o->uncertainty);
  sub->add_option_function<std::vector<std::string>>(
      "--cohesion",
      [o](const std::vector<std::string>& items) {
        o->cohesion = craterkit::cli::number_list("--cohesion", items);
      },
      "Cohesions Y of the scaling law, Pa (comma-separated); one age each");
  sub->add_option(
         "--prior", o->prior,
         "With --chronology: the prior is uniform in age, or in crater density (density: proportional to "
         "the flux, as craterstats)")
      ->check(CLI::IsMember({"age", "density"}))
      ->capture_default_str();
  sub->add_option(
      "--chronology", o->chronology,
      "Date with a published chronology system instead of the scaling law (data/chronology/NAME, "
      "e.g. moon_neukum2001, mars_neukum_ivanov2001, or a file): no law flags and no --cohesion then");
  sub->add_option("--population", o->population, "Impactor population in data/populations/ or a .toml file")
      ->capture_default_str();
  sub->add_option("--min-diameter", o->min_diameter,
                  "Smallest rim diameter of the fit range, m (default: smallest counted)");
  sub->add_option("--max-diameter", o->max_diameter, "Upper end of the fit range, m (default: none)");
  sub->add_option("--equilibrium", o->equilibrium,
                  "Cap counts at equilibrium: this fraction of the geometric saturation 1.54 D^-2 (Gault "
                  "1970), e.g. 0.05");
  sub->add_option(
         "--fractions", o->fractions,
         "How a crater's fraction (buffered counts) enters the Poisson likelihood: weight (it counts f) "
         "or whole (it counts 1, as craterstats' Poisson fit)")
      ->check(CLI::IsMember({"weight", "whole"}))
      ->capture_default_str();
  sub->add_option(
      "--plot", o->plot,
      "Write the standard figure (the counts with Poisson error bars and the isochrons, the fit range, "
      "the age densities) to this .png, .pdf or .svg");
  sub->add_option(
         "--presentation", o->presentation,
         "The counts in the figure: cumulative N(>D), differential dN/dD, or R (relative, D^3 dN/dD)")
      ->check(CLI::IsMember({"cumulative", "differential", "R"}))
      ->capture_default_str();
  sub->add_flag("--json", o->json, "Print JSON instead of a table");
  sub->footer(
      "Target density and gravity default to the body's; --impactor-density defaults to 2600 kg/m^3 and the "
      "impact speed to the body's mean speed for --region. Ages in years in JSON, Myr in the table. With "
      "--fit, the fit's covariance is carried into the age by --samples draws of the fitted constants: the "
      "law and total columns (scaling_law_uncertainty, total_uncertainty in JSON) beside the counting "
      "uncertainty.");
  sub->callback([o] { run_age(*o); });
}

const bool age_registered = craterkit::cli::register_command({"age", 40, &add_age_command});

}  // namespace
