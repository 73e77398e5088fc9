#pragma once
// JSON form of a scaling fit (what `craterkit fit --out` writes) and reading its law back, so that other
// commands can use a fitted law (`--fit FIT.json`, with `--group` for a grouped fit).
//
// A single fit (a table without grouping columns, or `--group-by none`):
// {
//   "form": "holsapple" | "hh2011",
//   "parameters": { "K1": {"value": v, "sigma": s, "fixed": b, "determined": b, "at_bound": b}, ...,
//                   ["Y": {...}] },          sigma is null for an undetermined parameter
//   "shared_strength": b, "chi2": x, "dof": n, "weighted": b, "sigma_scale": x,
//   "starts": n, "starts_at_minimum": n,
//   "correlation": {"names": [...], "matrix": [[...], ...]},
//   "residuals": [{"line": n, "observed": R, "model": R, "log_residual": r, "normalized": r}, ...]
// }
// A grouped fit (grouped_fit.hpp):
// {
//   "form": ..., "group_by": [columns], "pooled": {column: [values], ...}, "rows_read": n,
//   "excluded_rows": {"require_growth_ended": b, "lines": [...]}, "notes": [...],
//   "groups": [{"group": {"friction": "0.55", ...}, "rows": n, "cohesions": n, "strength_range": [lo, hi],
//               "growth_not_ended": [lines],
//               "fit": {a single fit as above} | null, ["not_fitted": "why", when fit is null]
//               "regime_counts": {"gravity": n, "transitional": n, "strength": n},
//               "regimes": [{"line": n, ["run": s,] ["growth_ended": b,] "regime": "gravity" | "transitional"
//               |
//                            "strength", "gravity_share": x, "strength_to_gravity": x | null}, ...]}, ...]
// }
// Group values are strings, exactly as written in the table; strength_to_gravity is null without gravity.
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "craterkit/scaling/fit.hpp"
#include "craterkit/scaling/grouped_fit.hpp"
#include "craterkit/scaling/law_uncertainty.hpp"

namespace craterkit::scaling {

nlohmann::json fit_to_json(const FitResult& fit);
nlohmann::json grouped_fit_to_json(const GroupedFitResult& result);

struct FittedLaw {
  ScalingLaw law;
  std::optional<double> strength;  // the fitted shared Y, if the fit had one
  LawCovariance covariance;        // of the constants; has_covariance() is false when the JSON gives none
  GroupKey group;                  // the group chosen from a grouped fit (empty for a single fit)
};

// "KEY=VALUE[,KEY=VALUE]" -> pairs; InputError naming the group selector otherwise.
GroupKey parse_group_selector(const std::string& text);

// Reads the law ("form", "parameters") and its covariance ("correlation" with the sigmas) of a fit JSON.
// A grouped fit needs `group` (parse_group_selector's text): its keys must be grouping columns and pick
// exactly one group, which must have been fitted; a single fit takes no group. InputError naming the file,
// the key and, for groups, the groups there are.
FittedLaw fitted_law_from_json(const nlohmann::json& json, const std::string& source_name,
                               const std::optional<std::string>& group = std::nullopt);
FittedLaw load_fitted_law(const std::filesystem::path& path,
                          const std::optional<std::string>& group = std::nullopt);

}  // namespace craterkit::scaling
