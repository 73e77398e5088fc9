// craterkit fit: Ceres fit of the point-source scaling law to a table of impacts and crater radii.
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "craterkit/common/atomic_file.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/fit.hpp"
#include "craterkit/scaling/fit_json.hpp"
#include "craterkit/scaling/radii_table.hpp"
#include "fit_report.hpp"

namespace craterkit::cli {
namespace {

struct FitCommandOptions {
  std::string table;
  std::string form = "holsapple";
  std::vector<std::string> fix;
  bool shared_strength = false;
  int starts = 12;
  std::optional<std::string> out;
  bool json = false;
};

std::pair<std::string, double> parse_fix(const std::string& text) {
  const auto eq = text.find('=');
  const std::string allowed = "NAME=VALUE with NAME one of K1, K2 (or H1, H2), mu, nu, Y and VALUE a number";
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) {
    throw InputError("--fix '" + text + "' is not allowed: use " + allowed);
  }
  const std::string name = text.substr(0, eq);
  const std::string value_text = text.substr(eq + 1);
  char* end = nullptr;
  const double value = std::strtod(value_text.c_str(), &end);
  if (end == value_text.c_str() || *end != '\0' || !std::isfinite(value)) {
    throw InputError("--fix '" + text + "': '" + value_text + "' is not a finite number; use " + allowed);
  }
  return {name, value};
}

std::string format_sigma(const scaling::FittedParameter& p) {
  if (p.fixed) return "(fixed)";
  if (!p.determined) return "(NOT DETERMINED by these data)";
  return fmt::format("+- {:.3g}{}", p.sigma, p.at_bound ? "  (at a bound: sigma not meaningful)" : "");
}

}  // namespace

// Text report of a fit (also used by `craterkit run`).
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

namespace {

void run_fit(const FitCommandOptions& options) {
  scaling::FitOptions fit_options;
  try {
    fit_options.form = scaling::form_from_string(options.form);
  } catch (const InputError&) {
    throw InputError("--form '" + options.form + "' is not allowed: use holsapple or hh2011");
  }
  for (const auto& text : options.fix) fit_options.fixed.push_back(parse_fix(text));
  if (options.starts < 1 || options.starts > 1000) {
    throw InputError(fmt::format("--starts {} is not allowed: must be between 1 and 1000", options.starts));
  }
  fit_options.starts = options.starts;
  fit_options.shared_strength = options.shared_strength;
  const auto table = scaling::read_radii_csv(options.table);
  const auto fit = scaling::fit_scaling_law(table, fit_options);
  const auto json = scaling::fit_to_json(fit);
  if (options.out) write_text_atomically(*options.out, json.dump(2) + "\n");
  if (options.json) {
    std::cout << json.dump(2) << "\n";
  } else {
    print_fit_report(fit, options.table, table.rows.size());
    if (options.out) fmt::print("  written: {}\n", *options.out);
  }
}

void add_fit_command(CLI::App& parent) {
  auto options = std::make_shared<FitCommandOptions>();
  auto* sub = parent.add_subcommand(
      "fit", "Fit the point-source scaling law (Ceres) to a CSV table of impacts and crater radii");
  sub->add_option("RADII.csv", options->table,
                  "Table with columns impactor_radius, impactor_density, velocity, target_density, gravity, "
                  "strength, crater_radius [, crater_radius_sigma] (SI)")
      ->required();
  sub->add_option("--form", options->form, "Parameterisation: holsapple (K1, K2) or hh2011 (H1, H2)")
      ->capture_default_str();
  // One NAME=VALUE per --fix (the flag repeats), so that a following positional is never swallowed.
  sub->add_option_function<std::string>(
         "--fix", [options](const std::string& value) { options->fix.push_back(value); },
         "Hold a parameter fixed: NAME=VALUE (repeat the flag for more), e.g. --fix nu=0.4")
      ->trigger_on_parse();
  sub->add_flag("--shared-strength", options->shared_strength,
                "Fit one strength Y shared by all rows instead of each row's strength column");
  sub->add_option("--starts", options->starts, "Number of starting points (1..1000)")->capture_default_str();
  sub->add_option("--out", options->out, "Write the fit JSON to this file (atomically)");
  sub->add_flag("--json", options->json, "Print the fit JSON instead of text");
  sub->callback([options] { run_fit(*options); });
}

const bool registered = register_command({"fit", 20, &add_fit_command});

}  // namespace
}  // namespace craterkit::cli
