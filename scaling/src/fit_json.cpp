// JSON form of a scaling fit and reading a fitted law back (see fit_json.hpp).
#include <cmath>
#include <fstream>
#include <limits>
#include <string>

#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/fit_json.hpp"

namespace craterkit::scaling {
namespace {

nlohmann::json finite_or_null(double value) {
  if (std::isfinite(value)) return value;
  return nullptr;
}

}  // namespace

nlohmann::json fit_to_json(const FitResult& fit) {
  nlohmann::json out;
  out["form"] = to_string(fit.form);
  nlohmann::json parameters = nlohmann::json::object();
  for (const auto& p : fit.parameters) {
    parameters[p.name] = {{"value", p.value},
                          {"sigma", finite_or_null(p.sigma)},
                          {"fixed", p.fixed},
                          {"determined", p.determined},
                          {"at_bound", p.at_bound}};
  }
  out["parameters"] = parameters;
  out["shared_strength"] = fit.shared_strength;
  out["chi2"] = fit.chi2;
  out["dof"] = fit.dof;
  out["weighted"] = fit.weighted;
  out["sigma_scale"] = fit.sigma_scale;
  out["starts"] = fit.starts;
  out["starts_at_minimum"] = fit.starts_at_minimum;
  nlohmann::json matrix = nlohmann::json::array();
  for (Eigen::Index r = 0; r < fit.correlation.rows(); ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index c = 0; c < fit.correlation.cols(); ++c)
      row.push_back(finite_or_null(fit.correlation(r, c)));
    matrix.push_back(row);
  }
  out["correlation"] = {{"names", fit.correlation_names}, {"matrix", matrix}};
  nlohmann::json residuals = nlohmann::json::array();
  for (const auto& r : fit.residuals) {
    residuals.push_back({{"line", r.line},
                         {"observed", r.observed},
                         {"model", r.model},
                         {"log_residual", r.log_residual},
                         {"normalized", r.normalized}});
  }
  out["residuals"] = residuals;
  return out;
}

FittedLaw fitted_law_from_json(const nlohmann::json& json, const std::string& source_name) {
  const auto fail = [&](const std::string& what) -> void { throw InputError(source_name + ": " + what); };
  if (!json.is_object()) fail("not a fit JSON object (written by `craterkit fit --out`)");
  if (!json.contains("form") || !json["form"].is_string()) fail("key 'form' is missing or not a string");
  FittedLaw out;
  try {
    out.law.form = form_from_string(json["form"].get<std::string>());
  } catch (const InputError& error) {
    fail(std::string("key 'form': ") + error.what());
  }
  if (!json.contains("parameters") || !json["parameters"].is_object()) fail("key 'parameters' is missing");
  const auto& parameters = json["parameters"];
  const auto value = [&](const std::string& name) -> double {
    if (!parameters.contains(name) || !parameters[name].is_object() || !parameters[name].contains("value") ||
        !parameters[name]["value"].is_number()) {
      throw InputError(source_name + ": key 'parameters." + name + ".value' is missing or not a number");
    }
    return parameters[name]["value"].get<double>();
  };
  out.law.coefficient_1 = value(coefficient_name(out.law.form, 1));
  out.law.coefficient_2 = value(coefficient_name(out.law.form, 2));
  out.law.mu = value("mu");
  out.law.nu = value("nu");
  try {
    validate(out.law);
  } catch (const InputError& error) {
    fail(error.what());
  }
  if (parameters.contains("Y")) out.strength = value("Y");
  return out;
}

FittedLaw load_fitted_law(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot open the fit JSON for reading");
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& error) {
    throw InputError(path.string() + ": not valid JSON: " + error.what());
  }
  return fitted_law_from_json(json, path.string());
}

}  // namespace craterkit::scaling
