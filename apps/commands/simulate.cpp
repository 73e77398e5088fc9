// craterkit simulate: runs an SPH problem described in TOML (data/examples/*.toml): snapshots,
// checkpoints, the conserved-quantities log and a summary (text, or JSON with --json).
#include <omp.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/common/toml_table.hpp"
#include "craterkit/impact/impact_run.hpp"
#include "craterkit/sph/run/standard_problem_config.hpp"
#include "json_output.hpp"
#include "output_checks.hpp"
#include "processes.hpp"

namespace craterkit::cli {
namespace {

struct SimulateOptions {
  std::string config;
  std::string out;
  int threads = 0;
  bool resume = false;
  bool overwrite = false;
  bool json = false;
  bool quiet = false;
  bool dry_run = false;
};

// A run summary as JSON; NaN (no crater found) as null.
nlohmann::json summary_json(const sph::RunSummary& s) {
  nlohmann::json phases = nlohmann::json::object();
  for (const auto& [name, seconds] : s.phase_seconds) phases[name] = seconds;
  nlohmann::json out = {{"name", s.name},
                        {"setup", s.setup},
                        {"particles", s.particles},
                        {"steps", s.steps},
                        {"steps_this_run", s.steps_this_run},
                        {"time", s.time},
                        {"wall_seconds", s.wall_seconds},
                        {"particle_updates_per_second", s.particle_updates_per_second},
                        {"mean_neighbours", s.mean_neighbours},
                        {"relative_energy_error", s.relative_energy_error},
                        {"relative_momentum_error", s.relative_momentum_error},
                        {"momentum_conserved", s.momentum_conserved},
                        {"bytes_per_particle", s.memory_use.total()},
                        {"bytes_per_particle_by_part",
                         {{"particle_fields", s.memory_use.particle_fields},
                          {"neighbour_lists", s.memory_use.neighbour_lists},
                          {"neighbour_search", s.memory_use.neighbour_search},
                          {"integrator", s.memory_use.integrator},
                          {"rate_pass", s.memory_use.rate_pass},
                          {"schedule", s.memory_use.schedule},
                          {"distributed", s.memory_use.distributed}}},
                        {"threads", s.threads},
                        {"processes", s.processes},
                        {"resumed", s.resumed},
                        {"neighbour_rebuilds", s.neighbour_rebuilds},
                        {"halos_found_anew", s.halos_found_anew},
                        {"phase_seconds", phases},
                        {"snapshots", s.snapshots},
                        {"checkpoint", s.checkpoint},
                        {"conservation_log", s.conservation_log}};
  if (s.transition_time > 0.0) {
    out["late_stage"] = {{"switched", s.late_stage},
                         {"transition_time", s.transition_time},
                         {"max_mach_at_transition", s.mach_at_transition},
                         {"max_mach_late_stage", s.late_stage_max_mach}};
  }
  if (!s.ejecta_log.empty()) {
    out["ejected_particles"] = s.ejected_particles;
    out["ejected_mass"] = s.ejected_mass;
    out["ejecta_log"] = s.ejecta_log;
  }
  return out;
}

nlohmann::json summary_json(const impact::ImpactRunSummary& s) {
  nlohmann::json out = summary_json(s.run);
  if (s.crater) {
    out["crater_radius"] = number_or_null(s.crater->crater_radius);
    out["crater_radius_uncertainty"] = number_or_null(s.crater->crater_radius_uncertainty);
    out["crater_depth"] = number_or_null(s.crater->depth);
    out["crater_wall_slope_deg"] = number_or_null(s.crater->wall_slope);
  }
  out["crater_growth_ended"] = s.crater_growth_ended;
  out["crater_growth_end_time"] = number_or_null(s.crater_growth_end_time.value_or(NAN));
  out["crater_growth_end_radius"] = number_or_null(s.crater_growth_end_radius.value_or(NAN));
  out["crater_json"] = s.crater_json;
  out["ejected_particles"] = s.run.ejected_particles;
  out["ejected_mass"] = s.run.ejected_mass;
  out["ejecta_log"] = s.run.ejecta_log;
  return out;
}

// --dry-run: what a run would simulate, to size it before it starts. Nothing is written.
void print_dry_run(const std::string& name, const std::string& setup, const sph::ProblemSetup& problem,
                   double end_time, const impact::ImpactSummary* impact, bool json) {
  const auto& p = problem.particles;
  std::size_t fixed = 0;
  for (const auto flag : p.flags) fixed += (flag & sph::particle_fixed) != 0 ? 1 : 0;
  if (json) {
    nlohmann::json out = {{"name", name},
                          {"setup", setup},
                          {"particles", p.size()},
                          {"fixed_particles", fixed},
                          {"end_time", end_time}};
    if (impact != nullptr) {
      out["target_particles"] = impact->target_particles;
      out["projectile_particles"] = impact->projectile_particles;
      out["t_transition"] = impact->transition_time;
      out["domain_radius"] = impact->domain_radius;
      out["particle_spacing"] = impact->particle_spacing;
      out["inner_spacing"] = impact->inner_spacing;
    }
    craterkit::cli::print_json(out);
    return;
  }
  if (impact != nullptr) fmt::print("{}", impact::describe_impact(*impact));
  fmt::print("{} ({}): {} particles ({} fixed), end time {:.6g} s; dry run, nothing simulated or written\n",
             name, setup, p.size(), fixed, end_time);
}

void print_crater(const impact::ImpactRunSummary& summary) {
  if (!summary.crater) return;
  fmt::print(
      "  crater radius {:.4g} +- {:.2g} m, depth {:.4g} m, wall slope {:.3g} deg{}; "
      "ejected {} particles ({:.4g} kg)\n",
      summary.crater->crater_radius, summary.crater->crater_radius_uncertainty, summary.crater->depth,
      summary.crater->wall_slope, summary.crater_growth_ended ? " (crater growth ended)" : "",
      summary.run.ejected_particles, summary.run.ejected_mass);
  if (!summary.crater_growth_ended && summary.crater_growth_end_time) {
    fmt::print(
        "  crater growth ended at t = {:.6g} s (radius {:.4g} m then); the run went on to t = {:.6g} s\n",
        *summary.crater_growth_end_time, *summary.crater_growth_end_radius, summary.run.time);
  }
}

// impact: the crater lines, for an impact run.
void print_summary(const sph::RunSummary& summary, const std::string& out,
                   const impact::ImpactRunSummary* impact = nullptr) {
  const std::string cores = summary.processes > 1
                                ? fmt::format("{} processes x {} threads", summary.processes, summary.threads)
                                : fmt::format("{} threads", summary.threads);
  fmt::print("{} ({}): {} particles, {} steps to t = {:.6g} s in {:.3f} s wall on {}\n", summary.name,
             summary.setup, summary.particles, summary.steps, summary.time, summary.wall_seconds, cores);
  fmt::print("  {:.4g} particle updates/s, {:.1f} neighbours/particle, {:.0f} bytes/particle\n",
             summary.particle_updates_per_second, summary.mean_neighbours, summary.memory_use.total());
  if (summary.momentum_conserved) {
    fmt::print("  relative energy error {:.3e}, relative momentum error {:.3e}\n",
               summary.relative_energy_error, summary.relative_momentum_error);
  } else {
    fmt::print(
        "  relative energy error {:.3e}; momentum not conserved here (gravity, fixed particles or mirror\n"
        "  planes act on the particles): it changed by {:.3e} of the particles' momentum\n",
        summary.relative_energy_error, summary.relative_momentum_error);
  }
  if (impact != nullptr) print_crater(*impact);
  if (summary.late_stage) {
    fmt::print("  late stage from t = {:.6g} s: largest Mach number {:.4g} at the switch, {:.4g} after\n",
               summary.transition_time, summary.mach_at_transition, summary.late_stage_max_mach);
  }
  if (!summary.checkpoint.empty()) fmt::print("  output in {} (checkpoint {})\n", out, summary.checkpoint);
  fmt::print("{}", summary.phase_table);
}

// The files a run writes into its output folder (docs/output.md), which --overwrite removes.
bool is_run_output(const std::string& name) {
  static const char* const fixed[] = {"checkpoint.h5",     "snapshots.xdmf",    "conservation.csv",
                                      "ejecta.csv",        "crater_growth.csv", "crater.json",
                                      "crater_profile.csv"};
  for (const char* f : fixed) {
    if (name == f) return true;
  }
  const bool snapshot = name.rfind("snap_", 0) == 0 && (name.ends_with(".h5") || name.ends_with(".xdmf"));
  const bool temporary = name.size() > 1 && name[0] == '.' && name.find(".tmp.") != std::string::npos;
  return snapshot || temporary;
}

// A new run (without --resume) goes into an empty or new folder; with --overwrite, the outputs of an
// earlier run in it are removed first (other files are left alone).
void prepare_output_folder(const SimulateOptions& options) {
  namespace fs = std::filesystem;
  check_output_folder("--out", options.out);
  std::error_code ec;
  if (options.resume || !fs::exists(options.out, ec)) return;
  std::vector<fs::path> outputs, others;
  for (const auto& entry : fs::directory_iterator(options.out)) {
    (is_run_output(entry.path().filename().string()) ? outputs : others).push_back(entry.path());
  }
  if (outputs.empty() && others.empty()) return;
  if (!options.overwrite) {
    const auto& first = outputs.empty() ? others.front() : outputs.front();
    throw InputError("--out " + options.out + ": not empty (it holds " + first.filename().string() +
                     (outputs.size() + others.size() > 1
                          ? " and " + std::to_string(outputs.size() + others.size() - 1) + " more"
                          : std::string()) +
                     "); a new run would mix its files with those. Give --overwrite to replace the outputs "
                     "of the run there, --resume to continue it, or another folder");
  }
  for (const auto& path : outputs) fs::remove(path);
}

void run_simulate_checked(const SimulateOptions& options);

// A folder this invocation created is removed again when the input turns out to be bad (status 2):
// nothing is written then.
void run_simulate(const SimulateOptions& given) {
  namespace fs = std::filesystem;
  SimulateOptions options = given;
  if (options.out.empty() && !options.dry_run && !options.resume) {
    // Without --out a run still keeps its output: a folder named after the configuration, in the current
    // directory, said on stderr before the run starts.
    options.out = fs::path(options.config).stem().string() + "-run";
    if (Processes::rank() == 0)
      std::cerr << "craterkit: no --out given: writing the output to " << options.out << "/\n";
  }
  std::error_code ec;
  const bool new_folder = !options.out.empty() && !options.dry_run && !fs::exists(options.out, ec);
  try {
    run_simulate_checked(options);
  } catch (const InputError&) {
    if (new_folder && fs::exists(options.out, ec) && !fs::exists(fs::path(options.out) / "checkpoint.h5", ec))
      fs::remove_all(options.out, ec);
    throw;
  }
}

void run_simulate_checked(const SimulateOptions& options) {
  check_threads("--threads", options.threads);
  if (options.resume && options.out.empty())
    throw InputError("--resume needs --out DIR (where the checkpoint is)");
  if (options.resume && options.overwrite)
    throw InputError("--resume and --overwrite exclude each other: continue the run in --out, or replace it");
  TomlTable root = TomlTable::parse_file(options.config);
  std::vector<std::string> setups = sph::standard_problem_names();
  setups.push_back("impact");
  const std::string setup = sph::read_problem_setup(root, setups);
  if (options.threads > 0) omp_set_num_threads(options.threads);
  sph::RunOptions run;
  run.output_directory = options.out;
  run.resume = options.resume;
  run.progress = !options.quiet;
  // Under mpirun: one simulation over the processes; process 0 writes and prints.
  const bool writer = Processes::rank() == 0;
  run.log = writer;
  if (setup == "impact") {
    const impact::ImpactConfig config = impact::parse_impact_config(root);
    run.configuration = root.values_read();
    if (!options.dry_run && !options.out.empty() && writer) prepare_output_folder(options);
    const std::unique_ptr<sph::Decomposition> decomposition = Processes::decomposition();
    run.decomposition = decomposition.get();
    Processes::wait_for_all();
    if (options.dry_run) {
      if (!writer) return;
      const impact::ImpactRun set_up = impact::build_impact_run(config);
      print_dry_run(config.simulation.name, setup, set_up.problem, config.simulation.run.end_time,
                    &set_up.summary, options.json);
      return;
    }
    const auto summary = impact::run_impact(config, run);
    if (!writer) return;
    if (options.json) {
      craterkit::cli::print_json(summary_json(summary));
      return;
    }
    print_summary(summary.run, options.out, &summary);
    return;
  }
  const sph::StandardProblemConfig config = sph::parse_standard_problem_config(root);
  run.configuration = root.values_read();
  if (!options.dry_run && !options.out.empty() && writer) prepare_output_folder(options);
  const std::unique_ptr<sph::Decomposition> decomposition = Processes::decomposition();
  run.decomposition = decomposition.get();
  Processes::wait_for_all();
  if (options.dry_run) {
    if (writer) {
      print_dry_run(config.simulation.name, setup, sph::build_standard_problem(config),
                    config.simulation.run.end_time, nullptr, options.json);
    }
    return;
  }
  const auto summary = sph::run_standard_problem(config, run);
  if (!writer) return;
  if (options.json) {
    craterkit::cli::print_json(summary_json(summary));
    return;
  }
  print_summary(summary, options.out);
}

void add_simulate_command(CLI::App& parent) {
  auto options = std::make_shared<SimulateOptions>();
  auto* sub = parent.add_subcommand("simulate",
                                    "Run an SPH simulation described by a TOML configuration (e.g. "
                                    "data/examples/sedov.toml)");
  sub->add_option("config", options->config, "Configuration file (TOML)")->required();
  sub->add_option("--out", options->out,
                  "Output directory (snapshots, checkpoint.h5, conservation.csv); default: CONFIG-run in the "
                  "current directory, e.g. sedov-run for sedov.toml");
  sub->add_option("--threads", options->threads, "OpenMP threads (default: all cores; at most 4 x cores)");
  sub->add_flag(
      "--resume", options->resume,
      "Continue from DIR/checkpoint.h5 when it exists (with the configuration it was started with)");
  sub->add_flag("--overwrite", options->overwrite,
                "Replace the outputs of an earlier run in --out DIR (a new run refuses a non-empty folder)");
  sub->add_flag("--json", options->json, "Print the final summary as a JSON object");
  sub->add_flag("--quiet", options->quiet, "No progress line");
  sub->add_flag("--dry-run", options->dry_run,
                "Build the set-up and report it (particle counts; for impacts the target, projectile and "
                "late-stage plan), then stop: nothing is simulated or written");
  sub->footer(
      "Prints a progress line on stderr and per-phase timings at the end. Snapshots are HDF5 with XDMF "
      "sidecars "
      "(open snapshots.xdmf in ParaView/VisIt). Exit status 2 for a bad configuration (the message names the "
      "key).");
  sub->callback([options] { run_simulate(*options); });
}

const bool simulate_registered = register_command({"simulate", 50, &add_simulate_command});

}  // namespace
}  // namespace craterkit::cli
