// craterkit report: the report of a sweep folder or of radii tables (report_builder.hpp, docs/report.md):
// the fitted scaling constants per group, the SCI crater under them and in the engine (against cohesion and
// friction), crater-formation rates and model ages of the Ryugu counts per cohesion, with figures.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "command_registry.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/radii_table.hpp"
#include "craterkit_version.hpp"
#include "group_by_flag.hpp"
#include "json_output.hpp"
#include "output_checks.hpp"
#include "report_builder.hpp"

namespace craterkit::cli {
namespace {

namespace fs = std::filesystem;

struct ReportCommandOptions {
  std::optional<std::string> sweep;
  std::vector<std::string> radii;
  std::string out = "craterkit-report";
  std::optional<std::string> group_by;
  bool overwrite = false;
  bool json = false;
  bool quiet = false;
};

// The tables named on the command line: DIR/radii.csv of a sweep folder, then every --radii FILE.
std::vector<fs::path> table_paths(const ReportCommandOptions& o) {
  std::vector<fs::path> paths;
  std::error_code ec;
  if (o.sweep) {
    const fs::path dir(*o.sweep);
    if (!fs::exists(dir, ec)) throw InputError("DIR " + *o.sweep + ": no such folder");
    if (!fs::is_directory(dir, ec)) {
      throw InputError("DIR " + *o.sweep +
                       ": is a file, not a sweep folder; give a radii table with --radii " + *o.sweep);
    }
    if (!fs::is_regular_file(dir / "radii.csv", ec)) {
      throw InputError(
          "DIR " + *o.sweep +
          ": holds no radii.csv, so it is not a sweep folder with finished runs (`craterkit sweep` "
          "writes DIR/radii.csv; `craterkit sweep --collect DIR` writes it from the runs there)");
    }
    paths.push_back(dir / "radii.csv");
  }
  for (const auto& file : o.radii) {
    if (!fs::exists(file, ec)) throw InputError("--radii " + file + ": no such file");
    if (!fs::is_regular_file(file, ec)) throw InputError("--radii " + file + ": is not a file");
    paths.push_back(file);
  }
  if (paths.empty())
    throw InputError("no input: give a sweep folder DIR (its radii.csv) or radii tables with --radii FILE");
  for (std::size_t i = 0; i < paths.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (fs::equivalent(paths[i], paths[j], ec))
        throw InputError("the table " + paths[i].string() + " is given twice (as " + paths[j].string() + ")");
    }
  }
  return paths;
}

// The output folder: new or empty; with --overwrite the files of an earlier report in it are replaced (other
// files are left alone). Checked before anything is computed.
void check_report_folder(const ReportCommandOptions& o) {
  check_output_folder("--out", o.out);
  std::error_code ec;
  if (!fs::exists(o.out, ec)) return;
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(o.out)) names.push_back(entry.path().filename().string());
  if (names.empty() || o.overwrite) return;
  std::sort(names.begin(), names.end());
  throw InputError("--out " + o.out + ": not empty (it holds " + names.front() +
                   (names.size() > 1 ? fmt::format(" and {} more", names.size() - 1) : std::string()) +
                   "); the report would mix its files with those. Give --overwrite to replace the files of "
                   "a report there, or another folder");
}

void remove_earlier_report(const fs::path& dir) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    if (entry.is_regular_file(ec) && is_report_output(entry.path().filename().string()))
      fs::remove(entry.path(), ec);
  }
}

void run_report(const ReportCommandOptions& o) {
  ReportOptions options;
  if (o.group_by) options.group_by = parse_group_by(*o.group_by);
  options.producer = craterkit_producer();
  options.progress = !o.quiet;
  const auto paths = table_paths(o);
  check_report_folder(o);
  std::vector<scaling::RadiiTable> tables;
  for (const auto& path : paths) {
    if (options.progress) std::cerr << "report: reading " << path.string() << "\n";
    tables.push_back(scaling::read_radii_csv(path));
  }
  const Report report = build_report(tables, options);
  fs::create_directories(o.out);
  if (o.overwrite) remove_earlier_report(o.out);
  const auto written = write_report(report, o.out, options.progress);
  print_written_report(written, o.json);
}

void add_report_command(CLI::App& parent) {
  auto o = std::make_shared<ReportCommandOptions>();
  auto* sub = parent.add_subcommand(
      "report",
      "Report on engine craters: fitted scaling constants per group, the SCI crater against cohesion and "
      "friction, crater-formation rates and Ryugu model ages per cohesion, with figures");
  sub->add_option("DIR", o->sweep, "A sweep folder (craterkit sweep --out DIR): its radii.csv");
  sub->add_option_function<std::string>(
         "--radii", [o](const std::string& file) { o->radii.push_back(file); },
         "A radii table (craterkit sweep's radii.csv, or data/radii/*.csv); repeat for several")
      ->trigger_on_parse();
  sub->add_option("--out", o->out, "Folder of the report (report.md, report.json, fit JSON, figures)")
      ->capture_default_str();
  sub->add_flag("--overwrite", o->overwrite,
                "Replace the files of an earlier report in --out (a new report refuses a non-empty folder)");
  sub->add_option("--group-by", o->group_by,
                  "Grouping columns to fit separately (comma-separated), or none for one fit over every row "
                  "(default: every grouping column of the table), as craterkit fit");
  sub->add_flag("--json", o->json, "Print report.json instead of report.md");
  sub->add_flag("--quiet", o->quiet, "No progress messages on stderr");
  sub->footer(
      "Figures need /usr/bin/python3 with matplotlib (scripts/plot_report.py); without them the report is "
      "written with its numbers and says which figures were skipped. Exit status 2 for bad input (the flag, "
      "file or column named), nothing written.");
  sub->callback([o] { run_report(*o); });
}

const bool report_registered = register_command({"report", 45, &add_report_command});

}  // namespace
}  // namespace craterkit::cli
