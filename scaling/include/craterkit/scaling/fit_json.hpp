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
//   "residual_summary": {"rows": n, "mean_log_residual": x, "rms_log_residual": x, "rms_normalized": x,
//                        "log_residual_quantiles": {"min": x, "p05": x, "median": x, "p95": x, "max": x},
//                        "largest": {"line": n, "log_residual": x, "normalized": x}}
// }
// Its size does not grow with the table: the rows' residuals (and regimes) go to a CSV file when asked for
// (write_residuals_csv), not into the JSON, which once repeated every row of the input.
// A grouped fit (grouped_fit.hpp):
// {
//   "form": ..., "group_by": [columns], "pooled": {column: [values], ...}, "rows_read": n,
//   "excluded_rows": {"require_growth_ended": b, "lines": [...]}, "notes": [...],
//   "groups": [{"group": {"friction": "0.55", ...}, "rows": n, "cohesions": n, "strength_range": [lo, hi],
//               "growth_not_ended": [lines],
//               "fit": {a single fit as above} | null, ["not_fitted": "why", when fit is null]
//               "regime_counts": {"gravity": n, "transitional": n, "strength": n}}, ...]
// }
// Group values are strings, exactly as written in the table.
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>

#include <nlohmann/json.hpp>

#include "craterkit/scaling/fit.hpp"
#include "craterkit/scaling/grouped_fit.hpp"
#include "craterkit/scaling/law_uncertainty.hpp"

namespace craterkit::scaling {

nlohmann::json fit_to_json(const FitResult& fit);
nlohmann::json grouped_fit_to_json(const GroupedFitResult& result);

// Every fitted row's residual and regime as CSV (what `craterkit fit --residuals FILE.csv` writes), one line
// per fitted row, the groups in the result's order and the rows in table order within each:
//   [the group_by columns,] line, [run,] [growth_ended,] observed, model, log_residual, normalized, regime,
//   gravity_share, strength_to_gravity
// (observed and model radii in m, ln R_model - ln R, its normalised form; the regime under the group's law
// as in the text report; strength_to_gravity empty without gravity). Numbers in the shortest form that
// reads back exactly. Written row by row, holding nothing per row. Needs the fits' residuals
// (FitOptions::keep_residuals; std::logic_error without them); rows left out (--require-growth-ended) and the
// rows of groups that were not fitted are not listed.
void write_residuals_csv(std::ostream& out, const RadiiTable& table, const GroupedFitResult& result);

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
