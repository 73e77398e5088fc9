// JSON form of a grouped fit (shape in fit_json.hpp).
#include <cmath>

#include "craterkit/scaling/fit_json.hpp"

namespace craterkit::scaling {
namespace {

nlohmann::json regime_json(const RowRegime& r) {
  nlohmann::json out{
      {"line", r.line},
      {"regime", to_string(r.regime.kind)},
      {"gravity_share", r.regime.gravity_share},
      {"strength_to_gravity", std::isfinite(r.strength_to_gravity) ? nlohmann::json(r.strength_to_gravity)
                                                                   : nlohmann::json(nullptr)}};
  if (r.run) out["run"] = *r.run;
  if (r.growth_ended) out["growth_ended"] = *r.growth_ended;
  return out;
}

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
  nlohmann::json regimes = nlohmann::json::array();
  for (const auto& r : group.regimes) regimes.push_back(regime_json(r));
  out["regimes"] = regimes;
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

}  // namespace craterkit::scaling
