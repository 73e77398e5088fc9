#pragma once
// The report of one or more radii tables (`craterkit report`, docs/report.md; the main job `craterkit run`
// writes its results with the same code): from the engine's craters to
//  - the scaling constants, one Ceres fit per group of each table, as `craterkit fit` makes it;
//  - the SCI crater under each fitted law, and the cohesion that makes the observed 7.25 +- 0.8 m;
//  - the engine's own SCI craters against cohesion per target (friction, porosity) with the cohesion of the
//    observed crater interpolated in the table, and against friction without cohesion;
//  - crater-formation rates on Ryugu against crater diameter per cohesion, relative to 1 Pa, and model ages
//    of the real Ryugu counts per cohesion, under every law fitted to more than one pi_2, as `craterkit
//    rates` and `craterkit age` compute them.
// Written to a folder: report.md, report.json (every number), the fits as `craterkit fit --out` writes them
// (fit.json, or fit_<table>.json for several tables) and the figures (report_figures.hpp).
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "craterkit/scaling/radii_table.hpp"
#include "report_figures.hpp"

namespace craterkit::cli {

// The cohesions (Pa) at which the fitted laws are evaluated: from cohesionless to the strongest of the
// shipped studies.
inline const std::vector<double> kReportCohesions{0.0, 0.05, 0.2, 0.5, 1.0, 2.0};

struct ReportOptions {
  // As `craterkit fit --group-by`: empty for every grouping column of each table, an empty list for one fit
  // over every row.
  std::optional<std::vector<std::string>> group_by;
  std::string title = "craterkit report";
  std::string producer;                             // "craterkit 0.1.0 (git ...)"
  std::string preamble;                             // Markdown sections before the report's own (main job)
  nlohmann::json extra = nlohmann::json::object();  // keys added to report.json (main job)
  bool progress = true;                             // progress messages on stderr
};

struct Report {
  std::string markdown;                                           // report.md without its figures
  nlohmann::json json;                                            // report.json without its figures
  std::vector<std::pair<std::string, nlohmann::json>> fit_files;  // file name, content
  std::vector<Figure> figures;                                    // the figures its numbers give
};

// Computes everything (nothing is written). InputError for a bad --group-by name, as `craterkit fit`.
Report build_report(const std::vector<scaling::RadiiTable>& tables, const ReportOptions& options);

struct WrittenReport {
  std::string markdown;  // report.md as written
  std::string json;      // report.json as written
  std::vector<std::filesystem::path> files;
  DrawnFigures figures;
};

// Writes the report into `dir` (an existing folder), each file atomically.
WrittenReport write_report(const Report& report, const std::filesystem::path& dir, bool progress);

// Prints what the command prints when done: report.json with `json`, else report.md and the files written.
void print_written_report(const WrittenReport& written, bool json);

// Whether a file of that name is one write_report writes (what --overwrite replaces), or a temporary one of
// those.
bool is_report_output(const std::string& file_name);

}  // namespace craterkit::cli
