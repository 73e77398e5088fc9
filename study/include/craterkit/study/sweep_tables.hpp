#pragma once
// The tables of a study (docs/sweep.md, "Output tables"), assembled from the run folders:
//   DIR/radii.csv  the input of `craterkit fit`: impactor_radius, impactor_density, velocity, target_density,
//                  gravity, strength, crater_radius, crater_radius_sigma (scaling/radii_table.hpp), then the
//                  grouping columns friction, porosity, resolution, one column per other varied axis, run and
//                  growth_ended; one row per finished run with a crater, in run order, numbers with 17
//                  significant digits, '#' header lines naming the study, the program and the command.
//                  Deterministic: nothing in it depends on when, where or in how many pieces the runs ran.
//   DIR/runs.csv   provenance, one row per run: status, attempts, crater, particles, steps, wall time.
// Both are written atomically.
#include <filesystem>
#include <string>
#include <vector>

#include "craterkit/study/run_result.hpp"

namespace craterkit::study {

// What the header lines say.
struct TableHeader {
  std::string study_name;
  std::string description;
  std::string producer;  // "craterkit 0.1.0 (git 1234abcd)"
  std::string command;   // "craterkit sweep example.toml --out example-run"
};

// The column names of radii.csv for a study's extra columns.
std::vector<std::string> radii_columns(const std::vector<std::string>& extra_columns);
std::string format_radii_csv(const TableHeader& header, const std::vector<std::string>& extra_columns,
                             const std::vector<RadiiRow>& rows);
std::string format_runs_csv(const std::vector<RunRecord>& runs);

struct CollectReport {
  TableHeader header;
  std::vector<RunRecord> runs;  // in run order
  std::size_t rows = 0;         // rows of radii.csv
  std::filesystem::path radii_csv, runs_csv;
};

// Reads DIR/sweep.json and every run's folder, writes DIR/radii.csv and DIR/runs.csv. InputError when DIR
// holds no sweep.json (not a study's output folder).
CollectReport collect(const std::filesystem::path& out, const std::string& producer);

// The end of a sweep for the user: counts, the tables, the failed runs; or a JSON object with --json
// (`started`: children this process started; -1 leaves it out, as for --collect).
std::string format_collect_summary(const CollectReport& report, long long started, bool json);

}  // namespace craterkit::study
