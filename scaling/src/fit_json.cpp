// JSON form of a scaling fit and reading a fitted law back (see fit_json.hpp).
#include <algorithm>
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
  const ResidualSummary& r = fit.residual_summary;
  out["residual_summary"] = {{"rows", r.rows},
                             {"mean_log_residual", r.mean_log_residual},
                             {"rms_log_residual", r.rms_log_residual},
                             {"rms_normalized", r.rms_normalized},
                             {"log_residual_quantiles",
                              {{"min", r.log_residual_min},
                               {"p05", r.log_residual_p05},
                               {"median", r.log_residual_median},
                               {"p95", r.log_residual_p95},
                               {"max", r.log_residual_max}}},
                             {"largest",
                              {{"line", r.largest_line},
                               {"log_residual", r.largest_log_residual},
                               {"normalized", r.largest_normalized}}}};
  return out;
}

namespace {

[[noreturn]] void fail(const std::string& source_name, const std::string& what) {
  throw InputError(source_name + ": " + what);
}

// The covariance of the constants from the sigmas and the correlation matrix; none when the JSON has no
// "correlation" (a hand-written law).
LawCovariance covariance_from_json(const nlohmann::json& json, const ScalingLaw& law,
                                   const std::string& source_name) {
  LawCovariance out;
  out.law = law;
  const auto& parameters = json["parameters"];
  for (const auto& name :
       {coefficient_name(law.form, 1), coefficient_name(law.form, 2), std::string("mu"), std::string("nu")}) {
    const auto& p = parameters[name];
    if (p.contains("fixed") && p["fixed"].is_boolean() && p["fixed"].get<bool>()) out.fixed.push_back(name);
    if (p.contains("determined") && p["determined"].is_boolean() && !p["determined"].get<bool>())
      out.undetermined.push_back(name);
  }
  if (!json.contains("correlation")) return out;
  const auto& correlation = json["correlation"];
  const auto bad = [&](const std::string& what) { fail(source_name, "key 'correlation': " + what); };
  if (!correlation.is_object() || !correlation.contains("names") || !correlation["names"].is_array() ||
      !correlation.contains("matrix") || !correlation["matrix"].is_array()) {
    bad("needs 'names' and 'matrix' arrays");
  }
  const auto& names = correlation["names"];
  const auto& matrix = correlation["matrix"];
  const std::size_t n = names.size();
  if (matrix.size() != n) bad("'matrix' must have one row per name");
  std::vector<std::size_t> keep;
  std::vector<double> sigma;
  for (std::size_t k = 0; k < n; ++k) {
    if (!names[k].is_string()) bad("'names' must be strings");
    const std::string name = names[k].get<std::string>();
    if (name == "Y") continue;  // a shared strength: marginalised (law_uncertainty.hpp)
    if (!parameters.contains(name) || !parameters[name].contains("sigma") ||
        !parameters[name]["sigma"].is_number()) {
      fail(source_name, "key 'parameters." + name + ".sigma' is missing or not a number, although '" + name +
                            "' is in the correlation matrix");
    }
    keep.push_back(k);
    out.names.push_back(name);
    sigma.push_back(parameters[name]["sigma"].get<double>());
  }
  const auto m = static_cast<Eigen::Index>(keep.size());
  out.covariance.resize(m, m);
  for (Eigen::Index r = 0; r < m; ++r) {
    const auto& row = matrix[keep[static_cast<std::size_t>(r)]];
    if (!row.is_array() || row.size() != n) bad("every row of 'matrix' must have one entry per name");
    for (Eigen::Index c = 0; c < m; ++c) {
      const auto& entry = row[keep[static_cast<std::size_t>(c)]];
      if (!entry.is_number()) bad("entries of 'matrix' must be numbers");
      out.covariance(r, c) =
          entry.get<double>() * sigma[static_cast<std::size_t>(r)] * sigma[static_cast<std::size_t>(c)];
    }
  }
  return out;
}

// The law of one single-fit object.
FittedLaw single_fit_law(const nlohmann::json& json, const std::string& source_name) {
  if (!json.is_object()) fail(source_name, "not a fit JSON object (written by `craterkit fit --out`)");
  if (!json.contains("form") || !json["form"].is_string())
    fail(source_name, "key 'form' is missing or not a string");
  FittedLaw out;
  try {
    out.law.form = form_from_string(json["form"].get<std::string>());
  } catch (const InputError& error) {
    fail(source_name, std::string("key 'form': ") + error.what());
  }
  if (!json.contains("parameters") || !json["parameters"].is_object())
    fail(source_name, "key 'parameters' is missing");
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
    fail(source_name, error.what());
  }
  if (parameters.contains("Y")) out.strength = value("Y");
  out.covariance = covariance_from_json(json, out.law, source_name);
  return out;
}

std::string selector_text(const GroupKey& key) {
  std::string out;
  for (const auto& [column, value] : key) out += (out.empty() ? "" : ",") + column + "=" + value;
  return out;
}

GroupKey group_key(const nlohmann::json& group, const std::string& source_name) {
  if (!group.is_object() || !group.contains("group") || !group["group"].is_object())
    fail(source_name, "every entry of 'groups' needs a 'group' object");
  GroupKey key;
  for (const auto& [column, value] : group["group"].items()) {
    if (!value.is_string()) fail(source_name, "group value of '" + column + "' is not a string");
    key.emplace_back(column, value.get<std::string>());
  }
  return key;
}

std::string group_list(const std::vector<GroupKey>& keys) {
  std::string out;
  for (const auto& key : keys) out += (out.empty() ? "" : "; ") + selector_text(key);
  return out;
}

// The group of a grouped fit that `selector` picks (see fitted_law_from_json).
FittedLaw grouped_fit_law(const nlohmann::json& json, const std::string& source_name,
                          const std::optional<std::string>& selector) {
  const auto& groups = json["groups"];
  if (!groups.is_array() || groups.empty()) fail(source_name, "key 'groups' must be a non-empty array");
  std::vector<GroupKey> keys;
  for (const auto& group : groups) keys.push_back(group_key(group, source_name));
  std::vector<std::string> columns;
  for (const auto& [column, value] : keys.front()) columns.push_back(column);
  const std::string listing = " groups: " + group_list(keys);
  if (!selector) {
    throw InputError(source_name + " holds " + std::to_string(keys.size()) +
                     " group fits; choose one with a group selector KEY=VALUE[,KEY=VALUE];" + listing);
  }
  const GroupKey wanted = parse_group_selector(*selector);
  for (const auto& [column, value] : wanted) {
    if (std::find(columns.begin(), columns.end(), column) == columns.end()) {
      std::string names;
      for (const auto& name : columns) names += (names.empty() ? "" : ", ") + name;
      throw InputError("group selector " + *selector + ": '" + column + "' is not a grouping column of " +
                       source_name + "; its grouping columns: " + names + ";" + listing);
    }
  }
  std::vector<std::size_t> matches;
  for (std::size_t g = 0; g < keys.size(); ++g) {
    const bool all = std::all_of(wanted.begin(), wanted.end(), [&](const auto& pair) {
      return std::find(keys[g].begin(), keys[g].end(), pair) != keys[g].end();
    });
    if (all) matches.push_back(g);
  }
  if (matches.empty())
    throw InputError("group selector " + *selector + " matches no group of " + source_name + ";" + listing);
  if (matches.size() > 1) {
    std::vector<GroupKey> matching;
    for (std::size_t g : matches) matching.push_back(keys[g]);
    throw InputError("group selector " + *selector + " matches " + std::to_string(matches.size()) +
                     " groups of " + source_name + " (" + group_list(matching) +
                     "); give more KEY=VALUE pairs");
  }
  const auto& group = groups[matches.front()];
  const std::string name = source_name + " group " + selector_text(keys[matches.front()]);
  if (!group.contains("fit") || group["fit"].is_null()) {
    const std::string why = group.contains("not_fitted") && group["not_fitted"].is_string()
                                ? group["not_fitted"].get<std::string>()
                                : std::string("no fit");
    throw InputError(name + " was not fitted (" + why + "); choose another;" + listing);
  }
  FittedLaw out = single_fit_law(group["fit"], name);
  out.group = keys[matches.front()];
  return out;
}

}  // namespace

GroupKey parse_group_selector(const std::string& text) {
  const std::string allowed =
      "use KEY=VALUE[,KEY=VALUE] with KEY a grouping column and VALUE as in the table";
  GroupKey out;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string pair = text.substr(start, comma - start);
    const auto eq = pair.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("group selector '" + text + "' is not allowed: " + allowed);
    const std::string key = pair.substr(0, eq);
    for (const auto& [seen, value] : out) {
      if (seen == key) throw InputError("group selector '" + text + "': '" + key + "' is given twice");
    }
    out.emplace_back(key, pair.substr(eq + 1));
    start = comma + 1;
  }
  return out;
}

FittedLaw fitted_law_from_json(const nlohmann::json& json, const std::string& source_name,
                               const std::optional<std::string>& group) {
  if (json.is_object() && json.contains("groups")) return grouped_fit_law(json, source_name, group);
  if (group) {
    throw InputError("group selector " + *group + " is not allowed: " + source_name +
                     " is a single fit without groups; give no group selector");
  }
  return single_fit_law(json, source_name);
}

FittedLaw load_fitted_law(const std::filesystem::path& path, const std::optional<std::string>& group) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot open the fit JSON for reading");
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& error) {
    throw InputError(path.string() + ": not valid JSON: " + error.what());
  }
  return fitted_law_from_json(json, path.string(), group);
}

}  // namespace craterkit::scaling
