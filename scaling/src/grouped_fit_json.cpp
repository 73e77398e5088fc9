// JSON form of a grouped fit and the residuals CSV (shapes in fit_json.hpp).
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "craterkit/scaling/fit_json.hpp"

namespace craterkit::scaling {
namespace {

nlohmann::json group_json(const GroupFit& group) {
  nlohmann::json key = nlohmann::json::object();
  for (const auto& [column, value] : group.key) key[column] = value;
  nlohmann::json out{{"group", key},
                     {"rows", group.lines.size()},
                     {"cohesions", group.cohesions},
                     {"strength_range", {group.min_strength, group.max_strength}},
                     {"growth_not_ended", group.growth_not_ended}};
  out["fit"] = group.fit ? fit_to_json(*group.fit) : nlohmann::json(nullptr);
  if (!group.fit) out["not_fitted"] = group.not_fitted;
  out["regime_counts"] = {{"gravity", group.regime_counts.gravity},
                          {"transitional", group.regime_counts.transitional},
                          {"strength", group.regime_counts.strength}};
  return out;
}

}  // namespace

nlohmann::json grouped_fit_to_json(const GroupedFitResult& result) {
  nlohmann::json pooled = nlohmann::json::object();
  for (const auto& column : result.pooled) pooled[column.name] = column.values;
  nlohmann::json groups = nlohmann::json::array();
  for (const auto& group : result.groups) groups.push_back(group_json(group));
  return {
      {"form", to_string(result.form)},
      {"group_by", result.group_by},
      {"pooled", pooled},
      {"rows_read", result.rows_read},
      {"excluded_rows", {{"require_growth_ended", result.require_growth_ended}, {"lines", result.excluded}}},
      {"notes", result.notes},
      {"groups", groups}};
}

namespace {

// The shortest text that reads back as the same double ("" for a non-finite value).
void put_number(std::ostream& out, double value) {
  if (!std::isfinite(value)) return;
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  out.write(text, end - text);
}

}  // namespace

void write_residuals_csv(std::ostream& out, const RadiiTable& table, const GroupedFitResult& result) {
  for (const auto& name : result.group_by) out << name << ",";
  out << "line";
  if (table.has_run()) out << "," << kRunColumn;
  if (table.has_growth_ended()) out << "," << kGrowthEndedColumn;
  out << ",observed,model,log_residual,normalized,regime,gravity_share,strength_to_gravity\n";
  for (const auto& group : result.groups) {
    if (!group.fit) continue;
    const FitResult& fit = *group.fit;
    if (fit.residuals.size() != group.rows.size()) {
      throw std::logic_error("write_residuals_csv: the fit kept no residuals (FitOptions::keep_residuals)");
    }
    for (std::size_t k = 0; k < group.rows.size(); ++k) {
      const ImpactRecord& row = table.rows[group.rows[k]];
      const FitResidual& r = fit.residuals[k];
      const RowRegime regime = row_regime(row, fit);
      for (const auto& [column, value] : group.key) out << value << ",";
      out << r.line;
      if (table.has_run()) out << "," << row.run.value_or("");
      if (table.has_growth_ended()) out << "," << (row.growth_ended.value_or(true) ? "true" : "false");
      for (const double value : {r.observed, r.model, r.log_residual, r.normalized}) {
        out << ",";
        put_number(out, value);
      }
      out << "," << to_string(regime.regime.kind) << ",";
      put_number(out, regime.regime.gravity_share);
      out << ",";
      put_number(out, regime.strength_to_gravity);
      out << "\n";
    }
  }
}

}  // namespace craterkit::scaling
