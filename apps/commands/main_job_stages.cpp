// The stages of the main job after the simulations (main_job_stages.hpp, docs/main_job.md).
#include "main_job_stages.hpp"

#include <cmath>
#include <map>
#include <numbers>

#include <fmt/format.h>

#include "craterkit/chronology/body.hpp"
#include "craterkit/chronology/crater_counts.hpp"
#include "craterkit/chronology/model_age.hpp"
#include "craterkit/chronology/population.hpp"
#include "craterkit/chronology/production.hpp"
#include "craterkit/chronology/scaled_production.hpp"
#include "craterkit/common/data_path.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/constant_sets.hpp"
#include "craterkit/scaling/fit_json.hpp"
#include "craterkit/scaling/grouped_fit.hpp"
#include "production_flags.hpp"

namespace craterkit::cli {
namespace {

namespace ck = chronology;

// The SCI experiment (docs/physics.md sections 4 and 6): 2 kg, 2700 kg/m^3, 2 km/s, vertical, into Ryugu.
constexpr double kSciMass = 2.0;             // kg
constexpr double kSciDensity = 2700.0;       // kg/m^3
constexpr double kSciVelocity = 2000.0;      // m/s
constexpr double kRyuguGravity = 1.4e-4;     // m/s^2
constexpr double kSciObservedRadius = 7.25;  // m, apparent radius (Arakawa et al. 2020)
constexpr double kSciObservedSigma = 0.8;    // m

// The published constants the fit is compared with.
constexpr const char* kPublishedSet = "jutzi2022_ryugu";
// The real count the ages are given for (data/craters/README.md).
constexpr const char* kRyuguCount = "craters/ryugu_global_hirata2020.csv";
// The crater diameters (rim-to-rim, m) of the rates and the reference cohesion (Pa) they are relative to.
const std::vector<double> kRateDiameters{20.0, 30.0, 40.0};
constexpr double kReferenceCohesion = 1.0;

std::string cohesion_text(double y) {
  return y == 0.0 ? std::string("0") : fmt::format("{:g}", y);
}

// The cohesion (Pa) whose SCI crater has radius `radius` under `law`; NaN when no cohesion gives it (the
// radius is at or above the cohesionless one).
double cohesion_for_radius(const scaling::ScalingLaw& law, const scaling::Impactor& sci,
                           scaling::Target target, double radius) {
  target.strength = 0.0;
  if (!(radius < scaling::crater_radius(law, sci, target))) return std::nan("");
  return scaling::solve_strength(law, radius, sci, target);
}

nlohmann::json number_or_null(double x) {
  return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr);
}

}  // namespace

nlohmann::json compare_with_shipped(const scaling::RadiiTable& live, const scaling::RadiiTable& shipped,
                                    std::string& report) {
  if (!live.has_run() || !shipped.has_run()) {
    throw InputError("comparing the live runs with " + shipped.source +
                     " needs the run column in both tables (tables written by craterkit sweep have it)");
  }
  std::map<std::string, double> shipped_radius;
  for (const auto& row : shipped.rows) shipped_radius[*row.run] = row.crater_radius;
  nlohmann::json rows = nlohmann::json::array();
  double largest = 0.0;
  report += fmt::format("\n## Live runs against the shipped table\n\n{} runs of {}, run again here:\n\n",
                        live.rows.size(), shipped.source);
  report += "| run | R live (m) | R shipped (m) | relative difference |\n|---|---|---|---|\n";
  for (const auto& row : live.rows) {
    const auto found = shipped_radius.find(*row.run);
    const double reference = found == shipped_radius.end() ? std::nan("") : found->second;
    const double difference = row.crater_radius / reference - 1.0;
    if (std::isfinite(difference)) largest = std::max(largest, std::abs(difference));
    rows.push_back({{"run", *row.run},
                    {"crater_radius", row.crater_radius},
                    {"shipped_crater_radius", number_or_null(reference)},
                    {"relative_difference", number_or_null(difference)}});
    report += fmt::format("| {} | {:.4f} | {} | {} |\n", *row.run, row.crater_radius,
                          std::isfinite(reference) ? fmt::format("{:.4f}", reference) : "not in the table",
                          std::isfinite(difference) ? fmt::format("{:.2e}", difference) : "-");
  }
  report += fmt::format(
      "\nLargest relative difference {:.2e}. Runs of one configuration now give the same crater byte for "
      "byte, with or without checkpoints; the shipped table's rows were measured with an engine whose "
      "checkpoints timed by the wall clock (`output.checkpoint_interval_seconds`, as in these runs) rebuilt "
      "the "
      "neighbour lists at steps that depended on the machine's load, and the late stage's granular flow "
      "amplified that round-off to a few per cent, the size of the fit's scatter (docs/main_job.md).\n",
      largest);
  return {{"source", shipped.source}, {"rows", rows}, {"largest_relative_difference", largest}};
}

scaling::FitResult fit_engine_radii(const scaling::RadiiTable& table, nlohmann::json& out,
                                    std::string& report) {
  scaling::FitOptions options;
  options.form = scaling::Form::hh2011;
  options.fixed = {{"nu", 0.4}};
  // Unweighted: a sweep's crater_radius_sigma is the measurement's resolution (a fraction of the rim
  // spacing), and every run of a study has the same number of spacings across its crater, so that error moves
  // all radii together (it is H1's systematic, docs/main_job.md) instead of scattering them; weighted by it,
  // chi^2 is far below its degrees of freedom and the slope mu comes out undetermined. The scatter about the
  // law sets the error bars instead.
  scaling::RadiiTable unweighted = table;
  for (auto& row : unweighted.rows) row.crater_radius_sigma.reset();
  const scaling::FitResult fit = scaling::fit_scaling_law(unweighted, options);
  const auto regimes = scaling::count_regimes(scaling::row_regimes(table.rows, fit));
  const auto published = scaling::load_constant_set(kPublishedSet);
  int growth_not_ended = 0;
  for (const auto& row : table.rows) growth_not_ended += row.growth_ended == false ? 1 : 0;
  double min_strength = INFINITY, max_strength = 0.0;
  for (const auto& row : table.rows) {
    min_strength = std::min(min_strength, row.target.strength);
    max_strength = std::max(max_strength, row.target.strength);
  }
  const double rms = fit.residual_summary.rms_log_residual;

  report += fmt::format(
      "\n## Scaling constants from the engine\n\nCeres fit of the point-source law (Housen & Holsapple 2011 "
      "form, "
      "nu = 0.4 fixed, unweighted) to {} craters of {} (cohesion {} to {} Pa; regimes under the fitted law: "
      "{} gravity, "
      "{} "
      "transitional, {} strength{}):\n\n",
      table.rows.size(), table.source, cohesion_text(min_strength), cohesion_text(max_strength),
      regimes.gravity, regimes.transitional, regimes.strength,
      growth_not_ended > 0 ? fmt::format("; {} still growing at their end time", growth_not_ended) : "");
  report += fmt::format("| constant | fitted | 1 sigma | {} |\n|---|---|---|---|\n", published.name);
  const std::map<std::string, double> published_values{{"H1", published.law.coefficient_1},
                                                       {"H2", published.law.coefficient_2},
                                                       {"mu", published.law.mu},
                                                       {"nu", published.law.nu}};
  nlohmann::json comparison = nlohmann::json::object();
  for (const auto& p : fit.parameters) {
    const auto reference = published_values.find(p.name);
    const std::string sigma = p.fixed         ? "fixed"
                              : !p.determined ? "undetermined"
                                              : fmt::format("{:.3g}", p.sigma);
    report +=
        fmt::format("| {} | {:.4g} | {}{} | {} |\n", p.name, p.value, sigma, p.at_bound ? " (at bound)" : "",
                    reference == published_values.end() ? "-" : fmt::format("{:g}", reference->second));
    if (reference != published_values.end()) comparison[p.name] = reference->second;
  }
  report += fmt::format(
      "\nchi^2 = {:.4g} for {} degrees of freedom; rms scatter of ln R about the law {:.3f} ({} of {} starts "
      "at the "
      "minimum).\n",
      fit.chi2, fit.dof, rms, fit.starts_at_minimum, fit.starts);
  out = scaling::fit_to_json(fit);
  out["source"] = table.source;
  out["published"] = {{"set", published.name}, {"citation", published.citation}, {"constants", comparison}};
  out["rms_log_residual"] = rms;
  out["regime_counts"] = {
      {"gravity", regimes.gravity}, {"transitional", regimes.transitional}, {"strength", regimes.strength}};
  out["growth_not_ended"] = growth_not_ended;
  return fit;
}

nlohmann::json sci_cohesion(const scaling::ScalingLaw& law, double target_density, std::string& report) {
  const scaling::Impactor sci{std::cbrt(3.0 * kSciMass / (4.0 * std::numbers::pi * kSciDensity)), kSciDensity,
                              kSciVelocity};
  scaling::Target target{target_density, kRyuguGravity, 0.0};
  report += fmt::format(
      "\n## The SCI crater\n\n{} kg at {} m/s into rho = {} kg/m^3 under g = {} m/s^2, by the fitted law; "
      "observed "
      "{} +- {} m (Arakawa et al. 2020).\n\n| cohesion (Pa) | R (m) | regime |\n|---|---|---|\n",
      kSciMass, kSciVelocity, target_density, kRyuguGravity, kSciObservedRadius, kSciObservedSigma);
  nlohmann::json rows = nlohmann::json::array();
  for (double y : kMainJobCohesions) {
    target.strength = y;
    const double radius = scaling::crater_radius(law, sci, target);
    const auto kind = scaling::to_string(scaling::regime(law, sci, target).kind);
    rows.push_back({{"cohesion", y}, {"crater_radius", radius}, {"regime", kind}});
    report += fmt::format("| {} | {:.3f} | {} |\n", cohesion_text(y), radius, kind);
  }
  // A larger crater needs a smaller cohesion: the observed range maps onto [Y(R + sigma), Y(R - sigma)].
  const double best = cohesion_for_radius(law, sci, target, kSciObservedRadius);
  const double low = cohesion_for_radius(law, sci, target, kSciObservedRadius + kSciObservedSigma);
  const double high = cohesion_for_radius(law, sci, target, kSciObservedRadius - kSciObservedSigma);
  const auto text = [](double y) {
    return std::isfinite(y) ? fmt::format("{:.3g} Pa", y) : std::string("none");
  };
  if (std::isfinite(best)) {
    report +=
        fmt::format("\nCohesion that makes the observed radius: {} ({} to {} for {} +- {} m).\n", text(best),
                    std::isfinite(low) ? text(low) : "0", text(high), kSciObservedRadius, kSciObservedSigma);
  } else {
    report += fmt::format(
        "\nNo cohesion makes the observed {} m: the cohesionless crater of this law is smaller{}.\n",
        kSciObservedRadius, std::isfinite(high) ? fmt::format(" (within 1 sigma below {})", text(high)) : "");
  }
  return {{"impactor_mass", kSciMass},
          {"impactor_density", kSciDensity},
          {"velocity", kSciVelocity},
          {"target_density", target_density},
          {"gravity", kRyuguGravity},
          {"observed_crater_radius", kSciObservedRadius},
          {"observed_crater_radius_sigma", kSciObservedSigma},
          {"cohesions", rows},
          {"cohesion_for_observed_radius", number_or_null(best)},
          {"cohesion_range_1sigma", {std::isfinite(low) ? low : 0.0, number_or_null(high)}}};
}

nlohmann::json relative_rates(const scaling::ScalingLaw& law, std::string& report) {
  const ck::Body body = ck::load_body("ryugu");
  const ProductionFlags flags;
  const auto population = ck::load_population("main_belt_approx_bottke2005");
  const auto setup = resolve_production_flags(flags, ScalingFlags{}, body, population);
  scaling::Target target{body.bulk_density, body.surface_gravity, 0.0};
  const double speed = ck::mean_speed(setup.speeds);
  report += fmt::format(
      "\n## Crater-formation rates on Ryugu\n\nMain-belt population {}, U = {:.0f} m/s, impactor density {} "
      "kg/m^3, rim diameter = {} apparent diameter; rate of craters larger than D, relative to {} Pa:\n\n"
      "| cohesion (Pa) |",
      population.name, speed, flags.impactor_density, setup.diameter.rim_to_apparent,
      cohesion_text(kReferenceCohesion));
  for (double d : kRateDiameters) report += fmt::format(" D = {:g} m |", d);
  report += "\n|---|";
  for (std::size_t i = 0; i < kRateDiameters.size(); ++i) report += "---|";
  report += "\n";
  const auto rate = [&](double y, double d) {
    target.strength = y;
    return ck::crater_production_rate(setup, ck::scaled_impactor_radius(law, target, flags.impactor_density),
                                      d);
  };
  std::vector<double> reference;
  for (double d : kRateDiameters) reference.push_back(rate(kReferenceCohesion, d));
  nlohmann::json rows = nlohmann::json::array();
  for (double y : kMainJobCohesions) {
    report += fmt::format("| {} |", cohesion_text(y));
    for (std::size_t i = 0; i < kRateDiameters.size(); ++i) {
      const double r = rate(y, kRateDiameters[i]);
      rows.push_back({{"cohesion", y},
                      {"crater_diameter", kRateDiameters[i]},
                      {"production_rate_per_km2_per_yr", r * 1e6},
                      {"relative_rate", r / reference[i]}});
      report += fmt::format(" {:.3g} |", r / reference[i]);
    }
    report += "\n";
  }
  return {{"body", body.name},
          {"population", population.name},
          {"impact_speed", speed},
          {"impactor_density", flags.impactor_density},
          {"rim_to_apparent", setup.diameter.rim_to_apparent},
          {"reference_cohesion", kReferenceCohesion},
          {"rows", rows}};
}

nlohmann::json model_ages(const scaling::ScalingLaw& law, std::string& report) {
  const ck::Body body = ck::load_body("ryugu");
  const ProductionFlags flags;
  const auto setup = resolve_production_flags(flags, ScalingFlags{}, body,
                                              ck::load_population("main_belt_approx_bottke2005"));
  const ck::CraterCounts counts = ck::read_crater_counts(data_file(kRyuguCount).string());
  scaling::Target target{body.bulk_density, body.surface_gravity, 0.0};
  report += fmt::format(
      "\n## Model ages\n\n{} (N(>=20 m) = 77 over Ryugu's surface, Hirata et al. 2020), Poisson likelihood, "
      "the "
      "production of the rates above:\n\n| cohesion (Pa) | median age (Myr) | 1 sigma (Myr) "
      "|\n|---|---|---|\n",
      kRyuguCount);
  nlohmann::json rows = nlohmann::json::array();
  for (double y : kMainJobCohesions) {
    target.strength = y;
    const auto production =
        ck::production_function(setup, ck::scaled_impactor_radius(law, target, flags.impactor_density));
    const auto age = ck::fit_model_age(counts, production, ck::AgeFitOptions{});
    rows.push_back({{"cohesion", y},
                    {"median_yr", age.median},
                    {"sigma1_yr", {age.sigma1_low, age.sigma1_high}},
                    {"reaches_max_age", age.reaches_max_age}});
    report += fmt::format("| {} | {:.3g} | {:.3g} to {:.3g}{} |\n", cohesion_text(y), age.median / 1e6,
                          age.sigma1_low / 1e6, age.sigma1_high / 1e6,
                          age.reaches_max_age ? " (reaches the age of the Solar System)" : "");
  }
  return {{"count", kRyuguCount}, {"body", body.name}, {"rows", rows}};
}

}  // namespace craterkit::cli
