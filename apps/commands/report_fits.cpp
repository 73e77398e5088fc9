// The report's scaling constants (report_fits.hpp).
#include "report_fits.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <set>

#include <fmt/format.h>

#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/constant_sets.hpp"
#include "craterkit/scaling/fit_json.hpp"
#include "json_output.hpp"
#include "progress_line.hpp"

namespace craterkit::cli {
namespace {

// The published laws set beside the fits: the Ryugu constants, and the two laboratory materials that bracket
// a weak granular target, dry sand (gravity regime) and perlite-sand (strength regime) (docs/scaling.md).
constexpr const char* kPublishedRyugu = "jutzi2022_ryugu";
constexpr const char* kPublishedSand = "hh2011_sand";
constexpr const char* kPublishedPerlite = "hh2011_perlite_sand";

// Points along pi_2 of a curve, and how far the curves reach beyond the group's rows (a factor each way).
constexpr int kCurvePoints = 61;
constexpr double kCurveMargin = 3.0;

std::string parameter_text(const scaling::FitResult& fit, const std::string& name) {
  const auto found = std::find_if(fit.parameters.begin(), fit.parameters.end(),
                                  [&](const scaling::FittedParameter& p) { return p.name == name; });
  if (found == fit.parameters.end()) return "-";
  const auto& p = *found;
  if (p.fixed) return fmt::format("{:.4g} (fixed)", p.value);
  if (!p.determined) return fmt::format("{:.4g} (undetermined)", p.value);
  return fmt::format("{:.4g} +- {:.2g}{}", p.value, p.sigma, p.at_bound ? " (at bound)" : "");
}

std::string published_text(double value) {
  return std::isnan(value) ? std::string("not given") : fmt::format("{:g}", value);
}

// The observed pi_R of a row: R (rho / m)^(1/3).
double observed_pi_R(const scaling::ImpactRecord& row) {
  return row.crater_radius * std::cbrt(row.target.density / scaling::impactor_mass(row.impactor));
}

std::vector<double> sorted_cohesions(const scaling::RadiiTable& table, const scaling::GroupFit& group) {
  std::set<double> values;
  for (const auto index : group.rows) values.insert(table.rows[index].target.strength);
  return {values.begin(), values.end()};
}

}  // namespace

std::string cohesion_text(double cohesion) {
  return fmt::format("{:g}", cohesion);
}

namespace {

// A grouping value as written in a table (a sweep writes numbers to 17 digits, 0.55000000000000004), shown
// to 6 significant digits when it is a number.
std::string value_label(const std::string& value) {
  char* end = nullptr;
  const double number = std::strtod(value.c_str(), &end);
  const bool numeric = !value.empty() && end == value.c_str() + value.size();
  return numeric ? fmt::format("{:.6g}", number) : value;
}

}  // namespace

std::string key_label(const scaling::GroupKey& key) {
  if (key.empty()) return "all rows";
  std::string out;
  for (const auto& [column, value] : key)
    out += fmt::format("{}{}={}", out.empty() ? "" : ", ", column, value_label(value));
  return out;
}

scaling::FitOptions report_fit_options() {
  scaling::FitOptions options;
  options.form = scaling::Form::hh2011;
  options.fixed = {{"nu", 0.4}};
  options.keep_residuals = false;
  return options;
}

TableFits fit_table(const scaling::RadiiTable& table, const std::optional<std::vector<std::string>>& group_by,
                    bool progress) {
  TableFits out;
  out.table = &table;
  scaling::GroupedFitOptions options;
  options.fit = report_fit_options();
  options.group_by = group_by;
  ProgressLine line(progress);
  options.fit.progress = [&](const scaling::FitProgress& p) {
    line.update(fmt::format("report: fitting {}: {} {} of {}, iteration {}  ({:.0f} s)", table.source,
                            p.stage, p.index + 1, p.count, p.iteration, line.seconds()));
  };
  // Unweighted: a sweep's crater_radius_sigma is the measurement's resolution (a fraction of the rim
  // spacing), and every run of a study has the same number of spacings across its crater, so that error moves
  // all radii together (it is H1's systematic, docs/main_job.md) instead of scattering them; weighted by it,
  // chi^2 is far below its degrees of freedom and the slope mu comes out undetermined. The scatter about the
  // law sets the error bars instead.
  scaling::RadiiTable unweighted = table;
  for (auto& row : unweighted.rows) row.crater_radius_sigma.reset();
  const bool one_fit = group_by ? group_by->empty() : table.group_columns.empty();
  try {
    out.result = scaling::fit_groups(unweighted, options);
  } catch (const std::runtime_error& error) {
    // A fit over every row that cannot be made (too few rows) leaves the table's other sections; a bad
    // grouping column, or a fit of a group, is the table's error as in `craterkit fit`.
    if (!one_fit) throw;
    out.not_fitted = error.what();
    return out;
  }
  line.finish();
  out.fit_json = out.result->grouped() ? scaling::grouped_fit_to_json(*out.result)
                                       : scaling::fit_to_json(out.result->groups.front().fit.value());
  return out;
}

int distinct_pi2(const scaling::RadiiTable& table, const scaling::GroupFit& group) {
  std::vector<double> values;
  for (const auto index : group.rows) {
    const auto& row = table.rows[index];
    values.push_back(scaling::pi_groups(row.impactor, row.target).pi2);
  }
  std::sort(values.begin(), values.end());
  int count = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i == 0 || values[i] > values[i - 1] * (1.0 + 1e-9)) ++count;
  }
  return count;
}

std::string fits_markdown(const std::vector<TableFits>& fits) {
  std::string md = fmt::format(
      "\n## Scaling constants\n\nCeres fit of the point-source law (Housen & Holsapple 2011 form, nu = 0.4 "
      "fixed, unweighted) to each group of a table's rows that share the values of its grouping columns: the "
      "fit of `craterkit fit TABLE --form hh2011 --fix nu=0.4` on the table without its crater_radius_sigma "
      "column (that sigma is the measurement's resolution, which moves every radius of a study together). "
      "Uncertainties are 1 sigma from the scatter about the law.\n");
  for (const auto& table_fits : fits) {
    const auto& table = *table_fits.table;
    md += fmt::format("\n### {}\n\n{} rows", table.source, table.rows.size());
    if (!table_fits.result) {
      md += fmt::format("; not fitted: {}\n", table_fits.not_fitted);
      continue;
    }
    const auto& result = *table_fits.result;
    if (result.grouped()) {
      std::string columns;
      for (const auto& c : result.group_by) columns += (columns.empty() ? "" : ", ") + c;
      md += fmt::format(", one fit per group of {}", columns);
    } else {
      md += ", one fit over every row";
    }
    for (const auto& pooled : result.pooled) {
      std::string values;
      for (const auto& v : pooled.values) values += (values.empty() ? "" : ", ") + value_label(v);
      md += fmt::format("; fitted together over {} = {}", pooled.name, values);
    }
    md += fmt::format("; fit file {}{}.\n\n", table_fits.fit_file,
                      result.grouped()
                          ? " (a group's law in other commands: --fit with --group KEY=VALUE,..., the "
                            "values as written in the table, in report.json)"
                          : "");
    md +=
        "| group | rows | cohesion (Pa) | H1 | H2 | mu | chi^2/dof | rms of ln R | regimes (gravity, "
        "transitional, strength) |\n|---|---|---|---|---|---|---|---|---|\n";
    std::string flagged;
    for (const auto& group : result.groups) {
      const std::string range =
          group.rows.empty()
              ? "-"
              : fmt::format("{} to {}", cohesion_text(group.min_strength), cohesion_text(group.max_strength));
      if (!group.fit) {
        md += fmt::format("| {} | {} | {} | not fitted: {} | | | | | |\n", key_label(group.key),
                          group.rows.size(), range, group.not_fitted);
        continue;
      }
      const auto& fit = *group.fit;
      const auto& counts = group.regime_counts;
      md += fmt::format("| {} | {} | {} | {} | {} | {} | {:.3g} | {:.3f} | {}, {}, {} |\n",
                        key_label(group.key), group.rows.size(), range, parameter_text(fit, "H1"),
                        parameter_text(fit, "H2"), parameter_text(fit, "mu"),
                        fit.dof > 0 ? fit.chi2 / fit.dof : std::numeric_limits<double>::quiet_NaN(),
                        fit.residual_summary.rms_log_residual, counts.gravity, counts.transitional,
                        counts.strength);
      if (!group.growth_not_ended.empty()) {
        flagged += fmt::format("\n{}: {} rows still growing at their end time (fitted).",
                               key_label(group.key), group.growth_not_ended.size());
      }
    }
    for (const char* name : {kPublishedRyugu, kPublishedSand, kPublishedPerlite}) {
      const auto set = scaling::load_constant_set(name);
      md += fmt::format("| {} (published) | | | {} | {} | {} | | | |\n", set.name,
                        published_text(set.law.coefficient_1), published_text(set.law.coefficient_2),
                        published_text(set.law.mu));
    }
    for (const auto& note : result.notes) md += "\nNote: " + note + "\n";
    if (!flagged.empty()) md += flagged + "\n";
  }
  return md;
}

nlohmann::json group_fit_json(const TableFits& fits, const scaling::GroupFit& group) {
  const auto& table = *fits.table;
  nlohmann::json key = nlohmann::json::object();
  for (const auto& [column, value] : group.key) key[column] = value;
  nlohmann::json out = {{"table", table.source},
                        {"group", key},
                        {"rows", group.rows.size()},
                        {"cohesions", sorted_cohesions(table, group)},
                        {"distinct_pi2", distinct_pi2(table, group)},
                        {"growth_not_ended", group.growth_not_ended},
                        {"fitted", group.fit.has_value()}};
  if (!group.fit) {
    out["not_fitted"] = group.not_fitted;
    return out;
  }
  out["fit"] = scaling::fit_to_json(*group.fit);
  out["regime_counts"] = {{"gravity", group.regime_counts.gravity},
                          {"transitional", group.regime_counts.transitional},
                          {"strength", group.regime_counts.strength}};
  return out;
}

nlohmann::json published_laws_json() {
  nlohmann::json out = nlohmann::json::array();
  for (const char* name : {kPublishedRyugu, kPublishedSand, kPublishedPerlite}) {
    const auto set = scaling::load_constant_set(name);
    const std::string c1 = scaling::coefficient_name(set.law.form, 1);
    const std::string c2 = scaling::coefficient_name(set.law.form, 2);
    out.push_back({{"set", set.name},
                   {"citation", set.citation},
                   {"form", scaling::to_string(set.law.form)},
                   {"constants",
                    {{c1, number_or_null(set.law.coefficient_1)},
                     {c2, number_or_null(set.law.coefficient_2)},
                     {"mu", set.law.mu},
                     {"nu", set.law.nu}}},
                   {"not_given", set.not_given}});
  }
  return out;
}

nlohmann::json scaled_radius_curves(const scaling::RadiiTable& table, const scaling::GroupFit& group) {
  nlohmann::json points = nlohmann::json::array();
  double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
  // The first row of each cohesion gives that cohesion's pi_3 and pi_4 for the curves.
  std::map<double, scaling::PiGroups> at_cohesion;
  for (const auto index : group.rows) {
    const auto& row = table.rows[index];
    const auto pi = scaling::pi_groups(row.impactor, row.target);
    at_cohesion.emplace(row.target.strength, pi);
    if (pi.pi2 > 0.0) {
      lo = std::min(lo, pi.pi2);
      hi = std::max(hi, pi.pi2);
    }
    points.push_back({{"pi2", pi.pi2},
                      {"pi3", pi.pi3},
                      {"pi4", pi.pi4},
                      {"pi_r", observed_pi_R(row)},
                      {"cohesion", row.target.strength},
                      {"run", row.run ? nlohmann::json(*row.run) : nlohmann::json(nullptr)}});
  }
  nlohmann::json out = {{"points", points}};
  if (!(hi > 0.0)) return out;  // no row with gravity: nothing to draw along pi_2
  lo /= kCurveMargin;
  hi *= kCurveMargin;
  std::vector<double> grid;
  for (int i = 0; i < kCurvePoints; ++i)
    grid.push_back(lo * std::pow(hi / lo, double(i) / (kCurvePoints - 1)));
  out["pi2_grid"] = grid;
  const double pi4 = at_cohesion.begin()->second.pi4;
  nlohmann::json fitted = nlohmann::json::array();
  if (group.fit) {
    const auto law = group.fit->law();
    for (const auto& [y, pi] : at_cohesion) {
      std::vector<double> values;
      for (double p : grid) values.push_back(scaling::pi_R(law, {p, pi.pi3, pi.pi4}));
      fitted.push_back({{"cohesion", y}, {"pi3", pi.pi3}, {"pi4", pi.pi4}, {"pi_r", values}});
    }
  }
  out["fitted"] = fitted;
  const auto sand = scaling::load_constant_set(kPublishedSand);
  std::vector<double> sand_values;
  for (double p : grid) sand_values.push_back(scaling::pi_R(sand.law, {p, 0.0, pi4}));
  out["sand"] = {{"set", sand.name}, {"pi4", pi4}, {"pi_r", sand_values}};
  const auto perlite = scaling::load_constant_set(kPublishedPerlite);
  nlohmann::json levels = nlohmann::json::array();
  for (const auto& [y, pi] : at_cohesion) {
    if (pi.pi3 > 0.0)
      levels.push_back(
          {{"cohesion", y}, {"pi3", pi.pi3}, {"pi_r", scaling::pi_R(perlite.law, {0.0, pi.pi3, pi.pi4})}});
  }
  out["perlite"] = {{"set", perlite.name}, {"levels", levels}};
  return out;
}

}  // namespace craterkit::cli
