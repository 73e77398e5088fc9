// craterkit sweep: runs a study of impacts (a cohesion x size grid, say) described by a study file, one
// `craterkit simulate` child per run, and tabulates their craters for `craterkit fit` (docs/sweep.md).
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "command_registry.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/study/dry_run.hpp"
#include "craterkit/study/slurm.hpp"
#include "craterkit/study/study_file.hpp"
#include "craterkit/study/study_plan.hpp"
#include "craterkit/study/sweep.hpp"
#include "craterkit/study/sweep_tables.hpp"
#include "craterkit_version.hpp"
#include "output_checks.hpp"

namespace craterkit::cli {
namespace {

struct SweepCommandOptions {
  std::string study;
  std::string out;
  int jobs = 1;
  int threads = 0;
  bool retry_failed = false;
  bool dry_run = false;
  bool json = false;
  std::string emit;
  std::optional<long long> task;
  std::string collect;
};

void check_flags(const SweepCommandOptions& o) {
  if (!o.collect.empty()) {
    if (!o.study.empty() || !o.out.empty() || o.dry_run || !o.emit.empty() || o.task || o.retry_failed) {
      throw InputError("--collect DIR takes no study file and no other flag than --json");
    }
    return;
  }
  if (o.study.empty()) throw InputError("a study file is required (craterkit sweep STUDY.toml --out DIR)");
  if (o.out.empty()) throw InputError("--out DIR is required: the folder of the study's runs and tables");
  check_output_folder("--out", o.out);
  if (o.jobs < 1) throw InputError(fmt::format("--jobs {}: must be >= 1", o.jobs));
  if (o.jobs > max_threads())
    throw InputError(fmt::format("--jobs {}: allowed 1 to {} (four times the processors available)", o.jobs,
                                 max_threads()));
  // --emit writes a script for other machines: its thread count is not bounded by this one's processors.
  if (o.emit.empty())
    check_threads("--threads", o.threads);
  else if (o.threads < 0)
    throw InputError(fmt::format("--threads {}: must be >= 1", o.threads));
  if (!o.emit.empty() && o.emit != "slurm")
    throw InputError("--emit '" + o.emit + "' is not allowed: use slurm");
  if (o.task && *o.task < 0) throw InputError(fmt::format("--task {}: must be >= 0", *o.task));
  const int modes = (o.dry_run ? 1 : 0) + (o.emit.empty() ? 0 : 1) + (o.task ? 1 : 0);
  if (modes > 1) throw InputError("--dry-run, --emit and --task exclude each other");
  if (o.task && o.jobs != 1) throw InputError("--task runs one run: --jobs is not allowed with it");
}

void run_sweep_command(const SweepCommandOptions& o) {
  check_flags(o);
  if (!o.collect.empty()) {
    const auto report = study::collect(o.collect, craterkit_producer());
    std::cout << study::format_collect_summary(report, -1, o.json);
    return;
  }
  const auto program = std::filesystem::read_symlink("/proc/self/exe");
  const study::Study s = study::load_study(o.study);
  const study::StudyPlan plan = study::plan_study(s, o.out);
  if (o.dry_run) {
    const auto counts = study::count_particles(s, program, o.jobs);
    std::cout << study::format_dry_run(plan, counts, o.json);
    return;
  }
  if (o.task && *o.task >= static_cast<long long>(plan.runs.size())) {
    throw InputError(fmt::format("--task {}: the study has runs 0 to {}", *o.task, plan.runs.size() - 1));
  }
  study::write_plan(plan,
                    o.task ? std::optional<std::size_t>(static_cast<std::size_t>(*o.task)) : std::nullopt);
  if (!o.emit.empty()) {
    const auto script = study::write_slurm_script(plan, {program, o.threads > 0 ? o.threads : 1});
    std::cout << fmt::format("wrote {} ({} array tasks); after them: craterkit sweep --collect {}\n",
                             script.string(), plan.runs.size(), plan.out.string());
    return;
  }
  study::SweepOptions options;
  options.jobs = o.jobs;
  options.child = {program, o.threads > 0 ? o.threads : study::default_threads(o.jobs)};
  options.retry_failed = o.retry_failed;
  options.producer = craterkit_producer();
  options.log = &std::cerr;
  if (o.task) {
    const auto record = study::run_task(plan, static_cast<std::size_t>(*o.task), options);
    if (o.json) {
      std::cout << fmt::format("{{\"task\": {}, \"run\": \"{}\", \"status\": \"{}\"}}\n", *o.task,
                               record.name, study::to_string(record.status));
    }
    if (record.status == study::RunStatus::failed || record.status == study::RunStatus::interrupted) {
      throw std::runtime_error(
          fmt::format("task {}: run {} {}", *o.task, record.name, study::to_string(record.status)));
    }
    return;
  }
  const auto report = study::run_sweep(plan, options);
  std::cout << study::format_collect_summary(report.tables, static_cast<long long>(report.started), o.json);
  std::size_t failed = 0, unfinished = 0;
  for (const auto& r : report.tables.runs) {
    failed += r.status == study::RunStatus::failed ? 1 : 0;
    unfinished += r.status == study::RunStatus::interrupted || r.status == study::RunStatus::pending ? 1 : 0;
  }
  if (failed > 0 || unfinished > 0) {
    throw std::runtime_error(
        fmt::format("of {} runs {} failed (their folders hold failed.json; --retry-failed runs "
                    "them again) and {} did not finish (run the sweep again)",
                    report.tables.runs.size(), failed, unfinished));
  }
}

void add_sweep_command(CLI::App& parent) {
  auto options = std::make_shared<SweepCommandOptions>();
  auto* sub = parent.add_subcommand(
      "sweep", "Run a study of impacts (axes such as cohesion x projectile size) and tabulate their craters");
  sub->add_option("study", options->study, "Study file (TOML, docs/sweep.md)");
  sub->add_option("--out", options->out,
                  "Output folder: DIR/runs/<name>/ per run, DIR/radii.csv, DIR/runs.csv");
  sub->add_option("--jobs", options->jobs, "Runs at once (default 1)");
  sub->add_option("--threads", options->threads, "OpenMP threads per run (default: cores / jobs; --emit: 1)");
  sub->add_flag("--retry-failed", options->retry_failed,
                "Run again the runs that failed before (failed.json)");
  sub->add_flag("--dry-run", options->dry_run,
                "Check the study and list its runs with their sizes and particle counts; run nothing");
  sub->add_flag("--json", options->json, "Print the final summary (or the --dry-run listing) as JSON");
  sub->add_option("--emit", options->emit, "Write DIR/sweep.slurm, a Slurm job array of the runs, and exit");
  sub->add_option("--task", options->task, "Run only run K (0-based; a Slurm array task)");
  sub->add_option("--collect", options->collect,
                  "Write DIR/radii.csv and DIR/runs.csv from the finished runs");
  sub->footer(
      "Each run is a `craterkit simulate` child in DIR/runs/<name>/; finished runs are skipped, interrupted "
      "ones "
      "resumed, failed ones skipped unless --retry-failed. Several sweeps (or Slurm tasks) on one folder "
      "never "
      "run a run twice. Exit status 2 for a bad study (the message names the key), 1 when a run failed.");
  sub->callback([options] { run_sweep_command(*options); });
}

const bool sweep_registered = register_command({"sweep", 55, &add_sweep_command});

}  // namespace
}  // namespace craterkit::cli
