// craterkit fit: Ceres fit of the point-source scaling law to a table of impacts and crater radii, one fit
// per group of the table's grouping columns (scaling/grouped_fit.hpp; docs/scaling.md).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
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
#include "craterkit/scaling/grouped_fit.hpp"
#include "craterkit/scaling/radii_table.hpp"
#include "fit_report.hpp"
#include "group_by_flag.hpp"
#include "json_output.hpp"
#include "output_checks.hpp"
#include "progress_line.hpp"

namespace craterkit::cli {
namespace {

struct FitCommandOptions {
  std::string table;
  std::string form = "holsapple";
  std::vector<std::string> fix;
  bool shared_strength = false;
  int starts = 12;
  std::optional<std::string> group_by;
  bool require_growth_ended = false;
  std::optional<std::string> out;
  std::optional<std::string> residuals;
  bool json = false;
  bool quiet = false;
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
  if (options.out) check_output_file("--out", *options.out);
  if (options.residuals) {
    check_output_file("--residuals", *options.residuals);
    if (options.out &&
        std::filesystem::absolute(*options.out) == std::filesystem::absolute(*options.residuals))
      throw InputError("--residuals " + *options.residuals + ": is also the --out file; give two files");
  }
  // The rows' residuals are kept only to be written (40 bytes a row).
  fit_options.keep_residuals = options.residuals.has_value();
  ProgressLine progress(!options.quiet);
  fit_options.progress = [&](const scaling::FitProgress& p) {
    progress.update(fmt::format("fit: {} {} of {}, iteration {}  ({:.0f} s)", p.stage, p.index + 1, p.count,
                                p.iteration, progress.seconds()));
  };
  fit_options.shared_strength = options.shared_strength;
  scaling::GroupedFitOptions grouped_options;
  grouped_options.fit = fit_options;
  if (options.group_by) grouped_options.group_by = parse_group_by(*options.group_by);
  grouped_options.require_growth_ended = options.require_growth_ended;
  const auto table = scaling::read_radii_csv(options.table, [&](const scaling::RadiiReadProgress& p) {
    progress.update(
        p.bytes_total > 0
            ? fmt::format("fit: reading {}: {} rows, {:.0f} % ({:.0f} s)", options.table, p.rows,
                          100.0 * double(p.bytes_read) / double(p.bytes_total), progress.seconds())
            : fmt::format("fit: reading {}: {} rows ({:.0f} s)", options.table, p.rows, progress.seconds()));
  });
  const auto result = scaling::fit_groups(table, grouped_options);
  progress.finish();
  if (options.residuals) {
    write_atomically(*options.residuals, [&](const std::filesystem::path& tmp) {
      std::ofstream file(tmp, std::ios::binary | std::ios::trunc);
      if (!file) throw std::runtime_error("cannot create a file in " + tmp.parent_path().string());
      scaling::write_residuals_csv(file, table, result);
      file.flush();
      if (!file) throw std::runtime_error("writing failed (disk full?)");
    });
  }
  // A table without grouping columns (or --group-by none) gives the single-fit JSON it always has.
  const auto json = craterkit::cli::with_version(
      result.grouped() ? scaling::grouped_fit_to_json(result)
                       : scaling::fit_to_json(result.groups.front().fit.value()));
  if (options.out) write_text_atomically(*options.out, json.dump(2) + "\n");
  if (options.json) {
    craterkit::cli::print_json(json);
  } else {
    print_grouped_fit_report(result, table);
    if (options.out) fmt::print("  written: {}\n", *options.out);
    if (options.residuals)
      fmt::print("  written: {} (every fitted row's residual and regime)\n", *options.residuals);
  }
}

void add_fit_command(CLI::App& parent) {
  auto options = std::make_shared<FitCommandOptions>();
  auto* sub = parent.add_subcommand(
      "fit", "Fit the point-source scaling law (Ceres) to a CSV table of impacts and crater radii");
  sub->add_option("RADII.csv", options->table,
                  "Table with columns impactor_radius, impactor_density, velocity, target_density, gravity, "
                  "strength, crater_radius [, crater_radius_sigma] (SI); optionally run, growth_ended and "
                  "grouping columns (e.g. friction, porosity, resolution), as `craterkit sweep` writes them")
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
  sub->add_option("--group-by", options->group_by,
                  "Grouping columns to fit separately (comma-separated), or none for one fit over every row "
                  "(default: every grouping column of the table)");
  sub->add_flag("--require-growth-ended", options->require_growth_ended,
                "Leave out the rows with growth_ended = false (by default they are fitted and flagged)");
  sub->add_option("--starts", options->starts, "Number of starting points (1..1000)")->capture_default_str();
  sub->add_option(
      "--out", options->out,
      "Write the fit JSON to this file (atomically): constants, covariance, summary statistics of the "
      "residuals");
  sub->add_option("--residuals", options->residuals,
                  "Write every fitted row's residual and regime to this CSV file (atomically)");
  sub->add_flag("--quiet", options->quiet, "No progress line on stderr (shown for long reads and fits)");
  sub->add_flag("--json", options->json, "Print the fit JSON instead of text");
  sub->callback([options] { run_fit(*options); });
}

const bool fit_registered = register_command({"fit", 20, &add_fit_command});

}  // namespace
}  // namespace craterkit::cli
