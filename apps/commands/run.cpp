// craterkit run: the main job, the whole chain on its embedded default (docs/main_job.md):
//  1. simulations: a study of impacts run live by the engine (`craterkit sweep`, study/sweep.hpp);
//  2. the Ceres fit of the point-source constants to the engine's craters;
//  3. the SCI crater and the cohesion that makes the observed radius;
//  4. crater-formation rates per cohesion and 5. model ages per cohesion.
// Stages 2-5 and the files they write are `craterkit report`'s (report_builder.hpp) on the job's table.
// By default the live study is two runs of the shipped cohesion x size study, which are checked against its
// table, and the fit uses that whole table (data/radii/); --full runs the whole study live, --study any
// study.
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "craterkit/common/atomic_file.hpp"
#include "craterkit/common/data_path.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/radii_table.hpp"
#include "craterkit/study/dry_run.hpp"
#include "craterkit/study/study_file.hpp"
#include "craterkit/study/study_plan.hpp"
#include "craterkit/study/sweep.hpp"
#include "craterkit_version.hpp"
#include "json_output.hpp"
#include "main_job_stages.hpp"
#include "report_builder.hpp"

namespace craterkit::cli {
namespace {

// The embedded default: two runs of the coarse cohesion x size study, live, and that study's shipped table.
constexpr const char* kDefaultStudy = "studies/main_job.toml";
constexpr const char* kFullStudy = "studies/cohesion_size_coarse.toml";
constexpr const char* kShippedTable = "radii/cohesion_size_coarse.csv";

struct MainJobOptions {
  std::string out = "craterkit-main-job";
  std::optional<std::string> study;
  bool full = false;
  int jobs = 0;
  int threads = 0;
  bool dry_run = false;
  bool json = false;
};

void check_options(const MainJobOptions& o) {
  if (o.full && o.study)
    throw InputError("--full and --study exclude each other: --full is the shipped study");
  if (o.jobs < 0) throw InputError(fmt::format("--jobs {}: must be >= 1", o.jobs));
  if (o.threads < 0) throw InputError(fmt::format("--threads {}: must be >= 1", o.threads));
  if (o.out.empty()) throw InputError("--out must name a folder");
  if (std::filesystem::exists(o.out) && !std::filesystem::is_directory(o.out)) {
    throw InputError("--out " + o.out + " is not allowed: it exists and is not a folder");
  }
}

// Runs the live study into DIR/sweep (finished runs of an earlier main job are reused) and returns its table.
scaling::RadiiTable run_simulations(const std::filesystem::path& study_file, const MainJobOptions& o,
                                    std::string& report) {
  const study::Study s = study::load_study(study_file);
  const study::StudyPlan plan = study::plan_study(s, std::filesystem::path(o.out) / "sweep");
  study::write_plan(plan, std::nullopt);
  study::SweepOptions options;
  options.jobs =
      o.jobs > 0 ? o.jobs : std::min<int>(study::available_cores(), static_cast<int>(plan.runs.size()));
  options.child = {std::filesystem::read_symlink("/proc/self/exe"),
                   o.threads > 0 ? o.threads : study::default_threads(options.jobs)};
  options.producer = craterkit_producer();
  options.log = &std::cerr;
  if (!o.json) {
    fmt::print("1. simulations: study {} ({} runs) in {}, {} at once, {} thread(s) each\n",
               study_file.string(), plan.runs.size(), plan.out.string(), options.jobs, options.child.threads);
    std::fflush(stdout);
  }
  const auto sweep = study::run_sweep(plan, options);
  std::size_t unusable = 0;
  for (const auto& r : sweep.tables.runs) unusable += r.status == study::RunStatus::done ? 0 : 1;
  if (unusable > 0) {
    throw std::runtime_error(fmt::format(
        "{} of {} runs of the study did not give a crater (see {}/runs.csv; their folders hold failed.json); "
        "run the main job again to resume",
        unusable, sweep.tables.runs.size(), plan.out.string()));
  }
  report +=
      fmt::format("\n## Simulations\n\nStudy {}: {} runs by the engine in {} (table {}).\n",
                  study_file.string(), plan.runs.size(), plan.out.string(), sweep.tables.radii_csv.string());
  return scaling::read_radii_csv(sweep.tables.radii_csv);
}

void run_main_job(const MainJobOptions& o) {
  check_options(o);
  const bool default_study = !o.full && !o.study;
  const std::filesystem::path study_file =
      o.study ? std::filesystem::path(*o.study) : data_file(o.full ? kFullStudy : kDefaultStudy);
  if (o.dry_run) {
    // The study's runs as the sweep would plan them, and what would be fitted; nothing run or written.
    const study::Study s = study::load_study(study_file);
    const study::StudyPlan plan = study::plan_study(s, std::filesystem::path(o.out) / "sweep");
    const int jobs = o.jobs > 0 ? o.jobs : study::available_cores();
    std::cout << study::format_dry_run(
        plan, study::count_particles(s, std::filesystem::read_symlink("/proc/self/exe"), jobs), o.json);
    if (!o.json) {
      fmt::print("then: the fit of {}, the SCI crater, rates and ages per cohesion into {}\n",
                 default_study ? data_file(kShippedTable).string() : (plan.out / "radii.csv").string(),
                 o.out);
    }
    return;
  }
  std::string preamble;
  nlohmann::json extra = {{"study", study_file.string()}};

  const scaling::RadiiTable live = run_simulations(study_file, o, preamble);
  scaling::RadiiTable table = live;
  if (default_study) {
    table = scaling::read_radii_csv(data_file(kShippedTable));
    extra["live_runs"] = compare_with_shipped(live, table, preamble);
  }
  if (!o.json) {
    fmt::print(
        "2. fit of the scaling constants to {} craters of {}; 3. the SCI crater, 4. rates and 5. ages per "
        "cohesion under the fitted law\n",
        table.rows.size(), table.source);
    std::fflush(stdout);
  }
  // The main job's report is `craterkit report`'s on its table, with one fit over every row: a study of one
  // target, or the law of the study's whole table when --study varies more.
  ReportOptions options;
  options.group_by = std::vector<std::string>{};
  options.title = "craterkit main job";
  options.producer = craterkit_producer();
  options.preamble = preamble;
  options.extra = extra;
  options.progress = true;
  const auto written = write_report(build_report({table}, options), o.out, options.progress);
  print_written_report(written, o.json);
}

void add_run_command(CLI::App& parent) {
  auto options = std::make_shared<MainJobOptions>();
  auto* sub = parent.add_subcommand(
      "run",
      "The main job: impacts simulated by the engine -> fitted scaling constants -> the SCI cohesion, "
      "crater-formation rates and model ages per cohesion");
  sub->add_option("--out", options->out,
                  "Folder of the runs and results (report.md, report.json, fit.json, figures)")
      ->capture_default_str();
  sub->add_flag(
      "--full", options->full,
      "Run the whole shipped cohesion x size study live (25 runs, about an hour on 2 cores) and fit it");
  sub->add_option("--study", options->study, "Run this study (docs/sweep.md) live and fit its craters");
  sub->add_option("--jobs", options->jobs, "Runs at once (default: the cores, at most the runs)");
  sub->add_option("--threads", options->threads, "OpenMP threads per run (default: cores / jobs)");
  sub->add_flag("--dry-run", options->dry_run,
                "Check the study and list its runs with their particle counts; run and write nothing");
  sub->add_flag("--json", options->json, "Print report.json instead of the report");
  sub->footer(
      "Runs finished by an earlier main job in the same --out are reused. Default: two runs of "
      "data/studies/cohesion_size_coarse.toml, checked against its shipped table data/radii/"
      "cohesion_size_coarse.csv, which the fit then uses.");
  sub->callback([options] { run_main_job(*options); });
}

const bool run_registered = register_command({"run", 5, &add_run_command});

}  // namespace
}  // namespace craterkit::cli
