// The report's SCI sections (report_sci.hpp).
#include "report_sci.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <map>
#include <set>

#include <fmt/format.h>

#include "craterkit/scaling/grouped_fit.hpp"
#include "json_output.hpp"
#include "report_fits.hpp"
#include "sci_impact.hpp"

namespace craterkit::cli {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string pa(double y) {
  return fmt::format("{:.3g}", y);
}

// The cohesion (Pa) whose SCI crater has radius `radius` under `law`; NaN when no cohesion gives it (the
// radius is at or above the cohesionless one).
double cohesion_for_radius(const scaling::ScalingLaw& law, scaling::Target target, double radius) {
  target.strength = 0.0;
  if (!(radius < scaling::crater_radius(law, sci_impactor(), target))) return kNaN;
  return scaling::solve_strength(law, radius, sci_impactor(), target);
}

// Where the polyline through `points` has R = level: x of every crossing, in order, each once.
std::vector<double> crossings_of(const std::vector<RadiusPoint>& points, double level) {
  std::vector<double> out;
  const auto add = [&](double x) {
    if (out.empty() || x > out.back()) out.push_back(x);
  };
  if (points.size() == 1 && points.front().radius == level) add(points.front().x);
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const auto& a = points[i];
    const auto& b = points[i + 1];
    if (a.radius == level) add(a.x);
    if ((a.radius - level) * (b.radius - level) < 0.0)
      add(a.x + (level - a.radius) * (b.x - a.x) / (b.radius - a.radius));
    if (b.radius == level) add(b.x);
  }
  return out;
}

// A series: the SCI craters of one table and one target against x.
struct Series {
  const scaling::RadiiTable* table = nullptr;
  scaling::GroupKey target;
  std::string label;
  std::vector<RadiusPoint> points;
  int merged = 0;  // rows merged into another of the same x (their mean is used)
};

// The rows of `table` that pass `keep`, as series by the grouping columns other than `varied`, with x from
// `x_of`; rows of the same target and x are merged into their mean.
std::vector<Series> collect_series(const scaling::RadiiTable& table, const std::string& varied,
                                   const std::function<bool(const scaling::ImpactRecord&)>& keep,
                                   const std::function<double(const scaling::ImpactRecord&)>& x_of) {
  std::map<scaling::GroupKey, std::size_t> index;
  std::vector<Series> out;
  for (const auto& row : table.rows) {
    if (!keep(row)) continue;
    scaling::GroupKey key;
    for (std::size_t c = 0; c < table.group_columns.size(); ++c) {
      if (table.group_columns[c] != varied) key.emplace_back(table.group_columns[c], row.group_values[c]);
    }
    auto [it, inserted] = index.emplace(key, out.size());
    if (inserted) out.push_back({&table, key, "", {}, 0});
    out[it->second].points.push_back(
        {x_of(row), row.crater_radius, row.crater_radius_sigma.value_or(0.0), row.run.value_or("")});
  }
  for (auto& series : out) {
    auto& p = series.points;
    std::stable_sort(p.begin(), p.end(), [](const auto& a, const auto& b) { return a.x < b.x; });
    std::vector<RadiusPoint> merged;
    for (std::size_t i = 0; i < p.size();) {
      std::size_t j = i;
      RadiusPoint sum{p[i].x, 0.0, 0.0, ""};
      for (; j < p.size() && p[j].x == p[i].x; ++j) {
        sum.radius += p[j].radius;
        sum.sigma += p[j].sigma;
        sum.run += (sum.run.empty() ? "" : "+") + p[j].run;
      }
      const double n = double(j - i);
      sum.radius /= n;
      sum.sigma /= n;
      series.merged += int(j - i) - 1;
      merged.push_back(sum);
      i = j;
    }
    p = merged;
  }
  // Labels: friction and porosity, and any other column whose value differs between the table's series.
  for (auto& series : out) {
    scaling::GroupKey shown;
    for (std::size_t k = 0; k < series.target.size(); ++k) {
      const auto& [column, value] = series.target[k];
      bool differs = false;
      for (const auto& other : out) differs = differs || other.target[k].second != value;
      if (column == "friction" || column == "porosity" || differs) shown.emplace_back(column, value);
    }
    series.label = shown.empty() ? std::string("every row") : key_label(shown);
  }
  return out;
}

std::vector<double> union_of_x(const std::vector<Series>& all) {
  std::set<double> xs;
  for (const auto& s : all) {
    for (const auto& p : s.points) xs.insert(p.x);
  }
  return {xs.begin(), xs.end()};
}

std::string radius_cell(const Series& s, double x) {
  for (const auto& p : s.points) {
    if (p.x == x) return fmt::format("{:.2f}", p.radius);
  }
  return "";
}

nlohmann::json target_json(const scaling::GroupKey& key) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [column, value] : key) out[column] = value;
  return out;
}

nlohmann::json points_json(const std::vector<RadiusPoint>& points, const char* x_name) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& p : points) {
    out.push_back({{x_name, p.x},
                   {"crater_radius", p.radius},
                   {"crater_radius_sigma", p.sigma > 0.0 ? nlohmann::json(p.sigma) : nlohmann::json(nullptr)},
                   {"run", p.run}});
  }
  return out;
}

// "0.13 Pa", or "none in range" and why.
std::string best_text(const Series& s, const ObservedCrossing& c) {
  if (c.crossings == 0 && s.points.size() == 1) {
    return fmt::format("none in range: one cohesion only ({:.2f} m at {} Pa)", s.points.front().radius,
                       pa(s.points.front().x));
  }
  if (c.crossings > 0) {
    return fmt::format("{} Pa{}", pa(c.best),
                       c.crossings > 1 ? fmt::format(" (first of {} crossings)", c.crossings) : "");
  }
  const auto largest = std::max_element(s.points.begin(), s.points.end(),
                                        [](const auto& a, const auto& b) { return a.radius < b.radius; });
  const auto smallest = std::min_element(s.points.begin(), s.points.end(),
                                         [](const auto& a, const auto& b) { return a.radius < b.radius; });
  if (largest->radius < kSciObservedRadius) {
    return fmt::format("none in range: smaller at every cohesion (largest {:.2f} m at {} Pa)",
                       largest->radius, pa(largest->x));
  }
  return fmt::format("none in range: larger at every cohesion (smallest {:.2f} m at {} Pa)", smallest->radius,
                     pa(smallest->x));
}

std::string band_text(const Series& s, const ObservedCrossing& c) {
  if (!std::isfinite(c.band_low)) return "none in range";
  if (s.points.size() == 1) return pa(c.band_low) + " Pa only (one cohesion)";
  const double first = s.points.front().x, last = s.points.back().x;
  const std::string low = fmt::format("{}{}", c.band_low == first && first > 0.0 ? "<=" : "", pa(c.band_low));
  const std::string high = fmt::format("{}{}", c.band_high == last ? ">=" : "", pa(c.band_high));
  return low == high ? low + " Pa" : low + " to " + high + " Pa";
}

}  // namespace

nlohmann::json sci_under_law(const scaling::ScalingLaw& law, double target_density,
                             const std::vector<double>& cohesions) {
  scaling::Target target{target_density, kSciGravity, 0.0};
  nlohmann::json rows = nlohmann::json::array();
  for (double y : cohesions) {
    target.strength = y;
    rows.push_back({{"cohesion", y},
                    {"crater_radius", scaling::crater_radius(law, sci_impactor(), target)},
                    {"regime", scaling::to_string(scaling::regime(law, sci_impactor(), target).kind)}});
  }
  // A larger crater needs a smaller cohesion: the observed range maps onto [Y(R + sigma), Y(R - sigma)].
  const double best = cohesion_for_radius(law, target, kSciObservedRadius);
  const double low = cohesion_for_radius(law, target, kSciObservedRadius + kSciObservedSigma);
  const double high = cohesion_for_radius(law, target, kSciObservedRadius - kSciObservedSigma);
  return {{"impactor_mass", kSciMass},
          {"impactor_density", kSciDensity},
          {"velocity", kSciVelocity},
          {"target_density", target_density},
          {"gravity", kSciGravity},
          {"observed_crater_radius", kSciObservedRadius},
          {"observed_crater_radius_sigma", kSciObservedSigma},
          {"cohesions", rows},
          {"cohesion_for_observed_radius", number_or_null(best)},
          {"cohesion_range_1sigma", {std::isfinite(low) ? low : 0.0, number_or_null(high)}}};
}

std::string sci_under_law_header(const std::vector<double>& cohesions) {
  std::string md = "| law | rho (kg/m^3) |";
  for (double y : cohesions) md += fmt::format(" R at {} Pa (m) |", pa(y));
  md += " cohesion for 7.25 m (1 sigma) |\n|---|---|";
  for (std::size_t i = 0; i < cohesions.size(); ++i) md += "---|";
  return md + "---|\n";
}

std::string sci_under_law_row(const std::string& label, const nlohmann::json& sci) {
  std::string md = fmt::format("| {} | {:g} |", label, sci["target_density"].get<double>());
  for (const auto& row : sci["cohesions"]) md += fmt::format(" {:.2f} |", row["crater_radius"].get<double>());
  const auto& best = sci["cohesion_for_observed_radius"];
  const auto& range = sci["cohesion_range_1sigma"];
  const std::string high = range[1].is_null() ? "none" : pa(range[1].get<double>()) + " Pa";
  if (best.is_null()) {
    md += fmt::format(" none: the cohesionless crater is smaller{} |",
                      range[1].is_null() ? "" : " (within 1 sigma up to " + high + ")");
  } else {
    md += fmt::format(" {} Pa ({} to {}) |", pa(best.get<double>()), pa(range[0].get<double>()), high);
  }
  return md + "\n";
}

ObservedCrossing cross_observed(const std::vector<RadiusPoint>& points) {
  ObservedCrossing out{kNaN, 0, kNaN, kNaN};
  if (points.empty()) return out;
  const auto best = crossings_of(points, kSciObservedRadius);
  out.crossings = static_cast<int>(best.size());
  if (!best.empty()) out.best = best.front();
  std::vector<double> inside;
  for (double level : {kSciObservedRadius - kSciObservedSigma, kSciObservedRadius + kSciObservedSigma}) {
    for (double x : crossings_of(points, level)) inside.push_back(x);
  }
  for (const auto& p : points) {
    if (std::abs(p.radius - kSciObservedRadius) <= kSciObservedSigma) inside.push_back(p.x);
  }
  if (!inside.empty()) {
    out.band_low = *std::min_element(inside.begin(), inside.end());
    out.band_high = *std::max_element(inside.begin(), inside.end());
  }
  return out;
}

nlohmann::json engine_sci_against_cohesion(const std::vector<const scaling::RadiiTable*>& tables,
                                           std::string& md) {
  std::vector<Series> all;
  nlohmann::json without = nlohmann::json::array();
  for (const auto* table : tables) {
    auto series = collect_series(
        *table, "", [](const scaling::ImpactRecord& row) { return is_sci_impact(row); },
        [](const scaling::ImpactRecord& row) { return row.target.strength; });
    if (series.empty()) without.push_back(table->source);
    for (auto& s : series) all.push_back(std::move(s));
  }
  md += fmt::format(
      "\n## The SCI crater in the engine, against cohesion\n\nThe engine's craters of the SCI impact "
      "({} kg at {} m/s under g = {} m/s^2) in each table, by target (its grouping columns); observed "
      "{} +- {} m (Arakawa et al. 2020). The cohesion of the observed crater is interpolated linearly "
      "between the table's cohesions, never beyond them; the 1-sigma column gives the lowest and highest "
      "cohesion whose interpolated crater lies within {:.2f}-{:.2f} m ('<=' and '>=' where that reaches "
      "the table's smallest or largest cohesion: it may extend beyond).\n\n",
      kSciMass, kSciVelocity, kSciGravity, kSciObservedRadius, kSciObservedSigma,
      kSciObservedRadius - kSciObservedSigma, kSciObservedRadius + kSciObservedSigma);
  nlohmann::json series_json = nlohmann::json::array();
  if (all.empty()) {
    md += "No table has rows of the SCI impact.\n";
  } else {
    const auto cohesions = union_of_x(all);
    md += "| table | target |";
    for (double y : cohesions) md += fmt::format(" R at {} Pa (m) |", pa(y));
    md += " cohesion for 7.25 m | cohesions within 1 sigma |\n|---|---|";
    for (std::size_t i = 0; i < cohesions.size(); ++i) md += "---|";
    md += "---|---|\n";
    for (const auto& s : all) {
      const auto c = cross_observed(s.points);
      md += fmt::format("| {} | {} |", s.table->source, s.label);
      for (double y : cohesions) md += fmt::format(" {} |", radius_cell(s, y));
      md += fmt::format(" {} | {} |\n", best_text(s, c), band_text(s, c));
      series_json.push_back(
          {{"table", s.table->source},
           {"target", target_json(s.target)},
           {"label", s.label},
           {"points", points_json(s.points, "cohesion")},
           {"merged_rows", s.merged},
           {"cohesion_for_observed_radius", number_or_null(c.best)},
           {"crossings", c.crossings},
           {"summary", best_text(s, c)},
           {"cohesion_band_1sigma",
            std::isfinite(c.band_low) ? nlohmann::json({c.band_low, c.band_high}) : nlohmann::json(nullptr)},
           {"band_reaches_smallest_cohesion", std::isfinite(c.band_low) && c.band_low == s.points.front().x},
           {"band_reaches_largest_cohesion",
            std::isfinite(c.band_high) && c.band_high == s.points.back().x}});
    }
    std::string notes;
    for (const auto& s : all) {
      if (s.merged > 0)
        notes += fmt::format("\n{}, {}: {} rows repeat a cohesion; their mean is used.\n", s.table->source,
                             s.label, s.merged);
    }
    for (const auto& source : without)
      notes += fmt::format("\n{} has no rows of the SCI impact.\n", source.get<std::string>());
    md += notes;
  }
  return {{"impact",
           {{"impactor_mass", kSciMass},
            {"impactor_density", kSciDensity},
            {"velocity", kSciVelocity},
            {"gravity", kSciGravity}}},
          {"observed_crater_radius", kSciObservedRadius},
          {"observed_crater_radius_sigma", kSciObservedSigma},
          {"series", series_json},
          {"tables_without_sci_rows", without}};
}

nlohmann::json engine_sci_against_friction(const std::vector<const scaling::RadiiTable*>& tables,
                                           std::string& md) {
  std::vector<Series> all;
  nlohmann::json without = nlohmann::json::array();
  for (const auto* table : tables) {
    const auto column = std::find(table->group_columns.begin(), table->group_columns.end(), "friction");
    if (column == table->group_columns.end()) {
      without.push_back(table->source);
      continue;
    }
    const auto position = static_cast<std::size_t>(column - table->group_columns.begin());
    auto series = collect_series(
        *table, "friction",
        [](const scaling::ImpactRecord& row) { return is_sci_impact(row) && row.target.strength == 0.0; },
        [position](const scaling::ImpactRecord& row) {
          return std::strtod(row.group_values[position].c_str(), nullptr);
        });
    for (auto& s : series) all.push_back(std::move(s));
  }
  md += fmt::format(
      "\n## The SCI crater in the engine, against friction\n\nThe engine's cohesionless SCI craters by the "
      "target's friction coefficient, per table and target; observed {} +- {} m.\n\n",
      kSciObservedRadius, kSciObservedSigma);
  nlohmann::json series_json = nlohmann::json::array();
  if (all.empty()) {
    md += "No table has cohesionless rows of the SCI impact with a friction column.\n";
  } else {
    const auto frictions = union_of_x(all);
    md += "| table | target |";
    for (double f : frictions) md += fmt::format(" R at f = {:g} (m) |", f);
    md += "\n|---|---|";
    for (std::size_t i = 0; i < frictions.size(); ++i) md += "---|";
    md += "\n";
    for (const auto& s : all) {
      md += fmt::format("| {} | {} |", s.table->source, s.label);
      for (double f : frictions) md += fmt::format(" {} |", radius_cell(s, f));
      md += "\n";
      series_json.push_back({{"table", s.table->source},
                             {"target", target_json(s.target)},
                             {"label", s.label},
                             {"points", points_json(s.points, "friction")},
                             {"merged_rows", s.merged}});
    }
  }
  return {{"observed_crater_radius", kSciObservedRadius},
          {"observed_crater_radius_sigma", kSciObservedSigma},
          {"series", series_json},
          {"tables_without_friction_column", without}};
}

}  // namespace craterkit::cli
