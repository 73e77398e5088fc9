// Text reports of scaling fits (see fit_report.hpp).
#include "fit_report.hpp"

#include <algorithm>
#include <map>
#include <set>

#include <fmt/format.h>

#include "join.hpp"

namespace craterkit::cli {
namespace {

std::string format_sigma(const scaling::FittedParameter& p) {
  if (p.fixed) return "(fixed)";
  if (!p.determined) return "(NOT DETERMINED by these data)";
  return fmt::format("+- {:.3g}{}", p.sigma, p.at_bound ? "  (at a bound: sigma not meaningful)" : "");
}

// "line 9 (run x)" for each line, with the run's name when the table has one; after the first 20 lines only
// how many more there are (a table of millions of rows may flag many).
std::string lines_with_runs(const std::vector<int>& lines, const scaling::RadiiTable& table) {
  constexpr std::size_t shown = 20;
  const std::vector<int> listed(lines.begin(),
                                lines.begin() + static_cast<std::ptrdiff_t>(std::min(shown, lines.size())));
  std::map<int, std::string> runs;
  if (table.has_run()) {
    const std::set<int> wanted(listed.begin(), listed.end());
    for (const auto& row : table.rows) {
      if (row.run && wanted.contains(row.line)) runs[row.line] = *row.run;
    }
  }
  std::vector<std::string> items;
  for (int line : listed) {
    items.push_back(runs.contains(line) ? fmt::format("line {} (run {})", line, runs[line])
                                        : fmt::format("line {}", line));
  }
  if (lines.size() > shown) items.push_back(fmt::format("and {} more", lines.size() - shown));
  return join(items);
}

// The rows of a fitted group: regime counts, and the rows fitted although their growth had not ended.
void print_group_rows(const scaling::GroupFit& group, const scaling::RadiiTable& table) {
  const auto& counts = group.regime_counts;
  fmt::print(
      "  regimes (strength/gravity term ratio <= 1/9: gravity, >= 9: strength): {} gravity, {} transitional, "
      "{} strength\n",
      counts.gravity, counts.transitional, counts.strength);
  if (!group.growth_not_ended.empty()) {
    fmt::print("  fitted with growth_ended = false (flagged; --require-growth-ended leaves them out): {}\n",
               lines_with_runs(group.growth_not_ended, table));
  }
}

}  // namespace

void print_fit_report(const scaling::FitResult& fit, const std::string& source, std::size_t rows) {
  fmt::print("Fit of the {} form to {} rows of {} ({})\n",
             fit.form == scaling::Form::holsapple ? "Holsapple (K1, K2)" : "Housen & Holsapple 2011 (H1, H2)",
             rows, source,
             fit.weighted ? "residuals in ln R weighted by crater_radius_sigma"
                          : "unweighted residuals in ln R; sigmas scaled by chi2/dof");
  for (const auto& p : fit.parameters)
    fmt::print("  {:<3} = {:<12.6g} {}\n", p.name, p.value, format_sigma(p));
  fmt::print(
      "  chi2 = {:.4g} for {} degrees of freedom (chi2/dof = {:.3g}); {} of {} starts reached the minimum\n",
      fit.chi2, fit.dof, fit.chi2 / fit.dof, fit.starts_at_minimum, fit.starts);
  if (!fit.correlation_names.empty()) {
    fmt::print("  correlation:");
    for (const auto& name : fit.correlation_names) fmt::print(" {:>7}", name);
    fmt::print("\n");
    for (Eigen::Index r = 0; r < fit.correlation.rows(); ++r) {
      fmt::print("  {:>11}", fit.correlation_names[static_cast<std::size_t>(r)]);
      for (Eigen::Index c = 0; c < fit.correlation.cols(); ++c) fmt::print(" {:7.3f}", fit.correlation(r, c));
      fmt::print("\n");
    }
  }
}

void print_grouped_fit_report(const scaling::GroupedFitResult& result, const scaling::RadiiTable& table) {
  if (result.grouped()) {
    fmt::print("Grouped fit: {} rows of {} in {} groups by {}\n", result.rows_read, result.source,
               result.groups.size(), join(result.group_by));
  }
  if (!result.excluded.empty()) {
    fmt::print("  left out (--require-growth-ended): {} rows with growth_ended = false: {}\n",
               result.excluded.size(), lines_with_runs(result.excluded, table));
  }
  for (const auto& column : result.pooled) {
    fmt::print("  fitted together over {}: {}\n", column.name, join(column.values));
  }
  for (const auto& note : result.notes) fmt::print("  note: {}\n", note);
  for (const auto& group : result.groups) {
    const std::string source =
        result.grouped() ? result.source + ", group " + scaling::describe(group.key) : result.source;
    if (result.grouped()) {
      fmt::print("\n== {}: {} rows, {} cohesions ({:g} to {:g} Pa)\n", scaling::describe(group.key),
                 group.lines.size(), group.cohesions, group.min_strength, group.max_strength);
    }
    if (!group.fit) {
      fmt::print("  NOT FITTED: {}\n", group.not_fitted);
      continue;
    }
    print_fit_report(*group.fit, source, group.lines.size());
    print_group_rows(group, table);
  }
}

}  // namespace craterkit::cli
