// The main job's comparison of its live runs with the shipped table (main_job_stages.hpp).
#include "main_job_stages.hpp"

#include <cmath>
#include <map>

#include <fmt/format.h>

#include "craterkit/common/input_error.hpp"
#include "json_output.hpp"

namespace craterkit::cli {
namespace {}  // namespace

nlohmann::json compare_with_shipped(const scaling::RadiiTable& live, const scaling::RadiiTable& shipped,
                                    std::string& report) {
  if (!live.has_run() || !shipped.has_run()) {
    throw InputError("comparing the live runs with " + shipped.source +
                     " needs the run column in both tables (tables written by craterkit sweep have it)");
  }
  std::map<std::string, double> shipped_radius;
  for (const auto& row : shipped.rows) shipped_radius[*row.run] = row.crater_radius;
  nlohmann::json rows = nlohmann::json::array();
  double largest = 0.0;
  report += fmt::format("\n## Live runs against the shipped table\n\n{} runs of {}, run again here:\n\n",
                        live.rows.size(), shipped.source);
  report += "| run | R live (m) | R shipped (m) | relative difference |\n|---|---|---|---|\n";
  for (const auto& row : live.rows) {
    const auto found = shipped_radius.find(*row.run);
    const double reference = found == shipped_radius.end() ? std::nan("") : found->second;
    const double difference = row.crater_radius / reference - 1.0;
    if (std::isfinite(difference)) largest = std::max(largest, std::abs(difference));
    rows.push_back({{"run", *row.run},
                    {"crater_radius", row.crater_radius},
                    {"shipped_crater_radius", number_or_null(reference)},
                    {"relative_difference", number_or_null(difference)}});
    report += fmt::format("| {} | {:.4f} | {} | {} |\n", *row.run, row.crater_radius,
                          std::isfinite(reference) ? fmt::format("{:.4f}", reference) : "not in the table",
                          std::isfinite(difference) ? fmt::format("{:.2e}", difference) : "-");
  }
  report += fmt::format(
      "\nLargest relative difference {:.2e}. Runs of one configuration now give the same crater byte for "
      "byte, with or without checkpoints; the shipped table's rows were measured with an engine whose "
      "checkpoints timed by the wall clock (`output.checkpoint_interval_seconds`, as in these runs) rebuilt "
      "the "
      "neighbour lists at steps that depended on the machine's load, and the late stage's granular flow "
      "amplified that round-off to a few per cent, the size of the fit's scatter (docs/main_job.md).\n",
      largest);
  return {{"source", shipped.source}, {"rows", rows}, {"largest_relative_difference", largest}};
}

}  // namespace craterkit::cli
