#pragma once
// The report's SCI sections (report.hpp): the SCI crater under a fitted law per cohesion, and the engine's
// own SCI craters in the tables, against cohesion per target (friction, porosity, ...) with the cohesion
// that makes the observed crater, and against friction without cohesion.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "craterkit/scaling/point_source.hpp"
#include "craterkit/scaling/radii_table.hpp"

namespace craterkit::cli {

// The SCI impact under `law` into a target of `target_density` at each of `cohesions`: crater radius and
// regime, and the cohesion whose crater is the observed 7.25 +- 0.8 m (scaling::solve_strength).
nlohmann::json sci_under_law(const scaling::ScalingLaw& law, double target_density,
                             const std::vector<double>& cohesions);

// One Markdown row of the table of sci_under_law results: "| label | rho | R... | cohesion |".
std::string sci_under_law_row(const std::string& label, const nlohmann::json& sci);
std::string sci_under_law_header(const std::vector<double>& cohesions);

// A crater radius against a varied quantity x (cohesion or friction), sorted by x.
struct RadiusPoint {
  double x = 0.0;
  double radius = 0.0;
  double sigma = 0.0;  // 0 when the table gives none
  std::string run;
};

// Where a piecewise-linear R(x) through `points` (sorted by x, one per x) meets the observed SCI crater:
// the first x with R = 7.25 m, how many crossings there are, and the lowest and highest x whose R lies in
// 7.25 +- 0.8 m (NaN where none). Interpolated linearly between the table's values, never beyond them.
struct ObservedCrossing {
  double best = 0.0;
  int crossings = 0;
  double band_low = 0.0;
  double band_high = 0.0;
};
ObservedCrossing cross_observed(const std::vector<RadiusPoint>& points);

// The engine's SCI craters of the tables against cohesion, one series per table and target (the values of the
// grouping columns), each with its observed crossing; and the cohesionless ones against friction, one series
// per table and target without friction. `markdown` receives both sections.
nlohmann::json engine_sci_against_cohesion(const std::vector<const scaling::RadiiTable*>& tables,
                                           std::string& markdown);
nlohmann::json engine_sci_against_friction(const std::vector<const scaling::RadiiTable*>& tables,
                                           std::string& markdown);

}  // namespace craterkit::cli
