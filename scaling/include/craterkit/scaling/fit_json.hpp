#pragma once
// JSON form of a scaling fit (what `craterkit fit --out FIT.json` writes) and reading its law back, so
// that other commands can use a fitted law (`--fit FIT.json`).
//
// {
//   "form": "holsapple" | "hh2011",
//   "parameters": { "K1": {"value": v, "sigma": s, "fixed": b, "determined": b, "at_bound": b}, ...,
//                   ["Y": {...}] },          sigma is null for an undetermined parameter
//   "shared_strength": b, "chi2": x, "dof": n, "weighted": b, "sigma_scale": x,
//   "starts": n, "starts_at_minimum": n,
//   "correlation": {"names": [...], "matrix": [[...], ...]},
//   "residuals": [{"line": n, "observed": R, "model": R, "log_residual": r, "normalized": r}, ...]
// }
#include <filesystem>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "craterkit/scaling/fit.hpp"

namespace craterkit::scaling {

nlohmann::json fit_to_json(const FitResult& fit);

struct FittedLaw {
  ScalingLaw law;
  std::optional<double> strength;  // the fitted shared Y, if the fit had one
};

// Reads the "form" and "parameters" of a fit JSON; InputError naming the file and key otherwise.
FittedLaw fitted_law_from_json(const nlohmann::json& json, const std::string& source_name);
FittedLaw load_fitted_law(const std::filesystem::path& path);

}  // namespace craterkit::scaling
