// The report's chronology under a fitted law (report_chronology.hpp).
#include "report_chronology.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "craterkit/chronology/body.hpp"
#include "craterkit/chronology/crater_counts.hpp"
#include "craterkit/chronology/model_age.hpp"
#include "craterkit/chronology/population.hpp"
#include "craterkit/chronology/production.hpp"
#include "craterkit/chronology/scaled_production.hpp"
#include "craterkit/common/data_path.hpp"
#include "production_flags.hpp"
#include "report_fits.hpp"

namespace craterkit::cli {
namespace {

namespace ck = chronology;

constexpr const char* kBody = "ryugu";
constexpr const char* kPopulation = "main_belt_approx_bottke2005";

// Crater diameters (rim-to-rim, m) of the rates: a 1-1.5-2-3-4-6 series from the smallest counted craters
// of Ryugu to its largest; the table of the report shows some of them.
const std::vector<double> kRateDiameters{10.0, 15.0, 20.0, 30.0, 40.0, 60.0, 100.0, 150.0, 200.0, 300.0};
const std::vector<double> kRateTableDiameters{10.0, 20.0, 30.0, 40.0, 100.0, 200.0};

// The real Ryugu counts and the diameter ranges they are dated over: a bin is used when its lower edge lies
// in [min, max] (chronology/model_age.hpp), so max = 99 m keeps the 20 m bin alone, the craters of 20-100 m.
struct RyuguCount {
  const char* file;
  const char* label;
  double min_diameter;
  double max_diameter;
};
const RyuguCount kRyuguCounts[] = {
    {"craters/ryugu_global_hirata2020.csv", "N(>=20 m)", 0.0, std::numeric_limits<double>::infinity()},
    {"craters/ryugu_global_hirata2020_20_100m.csv", "20-100 m", 0.0, 99.0},
    {"craters/ryugu_global_hirata2020_20_100m.csv", ">=100 m", 100.0,
     std::numeric_limits<double>::infinity()},
};

// Every tenth point of an age density's grid (and its last): enough to draw it, a tenth of the size.
constexpr std::size_t kDensityStride = 10;

// An age in the unit that suits it, with its 1-sigma range in the same unit.
std::string age_text(const ck::AgeEstimate& age) {
  const double m = age.median;
  const auto [scale, unit] = m < 1e3   ? std::pair{1.0, "yr"}
                             : m < 1e6 ? std::pair{1e3, "kyr"}
                             : m < 1e9 ? std::pair{1e6, "Myr"}
                                       : std::pair{1e9, "Gyr"};
  return fmt::format("{:.3g} {} [{:.3g}, {:.3g}]{}", m / scale, unit, age.sigma1_low / scale,
                     age.sigma1_high / scale,
                     age.reaches_max_age ? " (reaches the age of the Solar System)" : "");
}

struct RyuguProduction {
  ck::Body body;
  ProductionFlags flags;
  ck::ImpactorPopulation population;
  ck::ProductionSetup setup;
};

RyuguProduction ryugu_production() {
  RyuguProduction out{ck::load_body(kBody), ProductionFlags{}, ck::load_population(kPopulation), {}};
  out.setup = resolve_production_flags(out.flags, ScalingFlags{}, out.body, out.population);
  return out;
}

}  // namespace

nlohmann::json ryugu_rates(const scaling::ScalingLaw& law, const std::vector<double>& cohesions,
                           std::string& md) {
  const auto p = ryugu_production();
  scaling::Target target{p.body.bulk_density, p.body.surface_gravity, 0.0};
  const double speed = ck::mean_speed(p.setup.speeds);
  const auto rate = [&](double y, double d) {
    target.strength = y;
    return ck::crater_production_rate(p.setup,
                                      ck::scaled_impactor_radius(law, target, p.flags.impactor_density), d);
  };
  std::vector<double> reference;
  for (double d : kRateDiameters) reference.push_back(rate(kReferenceCohesion, d));
  md += "| cohesion (Pa) |";
  for (double d : kRateTableDiameters) md += fmt::format(" D = {:g} m |", d);
  md += "\n|---|";
  for (std::size_t i = 0; i < kRateTableDiameters.size(); ++i) md += "---|";
  md += "\n";
  nlohmann::json rows = nlohmann::json::array();
  for (double y : cohesions) {
    md += fmt::format("| {} |", cohesion_text(y));
    for (std::size_t i = 0; i < kRateDiameters.size(); ++i) {
      const double r = rate(y, kRateDiameters[i]);
      rows.push_back({{"cohesion", y},
                      {"crater_diameter", kRateDiameters[i]},
                      {"production_rate_per_km2_per_yr", r * 1e6},
                      {"relative_rate", r / reference[i]}});
      if (std::find(kRateTableDiameters.begin(), kRateTableDiameters.end(), kRateDiameters[i]) !=
          kRateTableDiameters.end())
        md += fmt::format(" {:.3g} |", r / reference[i]);
    }
    md += "\n";
  }
  return {{"body", p.body.name},
          {"population", p.population.name},
          {"population_approximate", p.population.approximate},
          {"impact_speed", speed},
          {"impactor_density", p.flags.impactor_density},
          {"rim_to_apparent", p.setup.diameter.rim_to_apparent},
          {"reference_cohesion", kReferenceCohesion},
          {"crater_diameters", kRateDiameters},
          {"rows", rows}};
}

nlohmann::json ryugu_ages(const scaling::ScalingLaw& law, const std::vector<double>& cohesions,
                          std::string& md) {
  const auto p = ryugu_production();
  scaling::Target target{p.body.bulk_density, p.body.surface_gravity, 0.0};
  std::vector<ck::ProductionFunction> productions;
  for (double y : cohesions) {
    target.strength = y;
    productions.push_back(
        ck::production_function(p.setup, ck::scaled_impactor_radius(law, target, p.flags.impactor_density)));
  }
  nlohmann::json units = nlohmann::json::array();
  std::vector<std::vector<std::string>> cells(cohesions.size());
  std::vector<std::string> headers;
  for (const auto& count : kRyuguCounts) {
    const ck::CraterCounts counts = ck::read_crater_counts(data_file(count.file).string());
    ck::AgeFitOptions options;
    options.min_diameter = count.min_diameter;
    options.max_diameter = count.max_diameter;
    nlohmann::json rows = nlohmann::json::array();
    double craters = 0.0;
    for (std::size_t i = 0; i < cohesions.size(); ++i) {
      const auto age = ck::fit_model_age(counts, productions[i], options);
      craters = age.craters_in_range;
      std::vector<double> grid, density;
      for (std::size_t k = 0; k < age.age_grid.size(); ++k) {
        if (k % kDensityStride == 0 || k + 1 == age.age_grid.size()) {
          grid.push_back(age.age_grid[k]);
          density.push_back(age.density[k]);
        }
      }
      rows.push_back({{"cohesion", cohesions[i]},
                      {"median_yr", age.median},
                      {"mode_yr", age.mode},
                      {"sigma1_yr", {age.sigma1_low, age.sigma1_high}},
                      {"sigma2_yr", {age.sigma2_low, age.sigma2_high}},
                      {"reaches_max_age", age.reaches_max_age},
                      {"age_yr", grid},
                      {"density_per_yr", density}});
      cells[i].push_back(age_text(age));
    }
    headers.push_back(fmt::format("{} ({:g} craters)", count.label, craters));
    units.push_back({{"count", count.file},
                     {"label", count.label},
                     {"craters", craters},
                     {"min_diameter", count.min_diameter},
                     {"max_diameter", std::isfinite(count.max_diameter) ? nlohmann::json(count.max_diameter)
                                                                        : nlohmann::json(nullptr)},
                     {"rows", rows}});
  }
  md += "| cohesion (Pa) |";
  for (const auto& h : headers) md += " " + h + " |";
  md += "\n|---|";
  for (std::size_t i = 0; i < headers.size(); ++i) md += "---|";
  md += "\n";
  for (std::size_t i = 0; i < cohesions.size(); ++i) {
    md += fmt::format("| {} |", cohesion_text(cohesions[i]));
    for (const auto& cell : cells[i]) md += " " + cell + " |";
    md += "\n";
  }
  return {{"body", p.body.name},
          {"population", p.population.name},
          {"population_approximate", p.population.approximate},
          {"units", units}};
}

}  // namespace craterkit::cli
