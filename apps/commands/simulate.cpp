// craterkit simulate: runs an SPH problem described in TOML (data/examples/*.toml): snapshots,
// checkpoints, the conserved-quantities log and a summary (text, or JSON with --json).
#include <omp.h>

#include <cmath>
#include <iostream>
#include <memory>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "command_registry.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/sph/io/config.hpp"
#include "craterkit/sph/solver/simulation.hpp"

namespace craterkit::cli {
namespace {

struct SimulateOptions {
  std::string config;
  std::string out;
  int threads = 0;
  bool resume = false;
  bool json = false;
  bool quiet = false;
  bool dry_run = false;
};

// NaN (no crater found) as null.
nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
}

nlohmann::json summary_json(const sph::SimulationSummary& s) {
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
                        {"bytes_per_particle", s.bytes_per_particle},
                        {"threads", s.threads},
                        {"resumed", s.resumed},
                        {"neighbour_rebuilds", s.neighbour_rebuilds},
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
  if (s.crater) {
    out["crater_radius"] = number_or_null(s.crater->crater_radius);
    out["crater_radius_uncertainty"] = number_or_null(s.crater->crater_radius_uncertainty);
    out["crater_depth"] = number_or_null(s.crater->depth);
    out["crater_growth_ended"] = s.crater_growth_ended;
    out["crater_growth_end_time"] = number_or_null(s.crater_growth_end_time.value_or(NAN));
    out["crater_growth_end_radius"] = number_or_null(s.crater_growth_end_radius.value_or(NAN));
    out["crater_json"] = s.crater_json;
    out["ejected_particles"] = s.ejected_particles;
    out["ejected_mass"] = s.ejected_mass;
    out["ejecta_log"] = s.ejecta_log;
  }
  return out;
}

void run_simulate(const SimulateOptions& options) {
  if (options.threads < 0)
    throw InputError("--threads " + std::to_string(options.threads) + ": must be >= 1");
  if (options.resume && options.out.empty())
    throw InputError("--resume needs --out DIR (where the checkpoint is)");
  const sph::SimulationConfig config = sph::load_simulation_config(options.config);
  if (options.threads > 0) omp_set_num_threads(options.threads);
  if (options.dry_run) {
    // The set-up only: what a run would simulate, to size it before it starts. Nothing is written.
    const sph::Scenario scenario = sph::build_scenario(config);
    const auto& p = scenario.problem.particles;
    std::size_t fixed = 0;
    for (const auto flag : p.flags) fixed += (flag & sph::particle_fixed) != 0 ? 1 : 0;
    if (options.json) {
      nlohmann::json out = {{"name", config.name},
                            {"setup", sph::setup_name(config.setup)},
                            {"particles", p.size()},
                            {"fixed_particles", fixed},
                            {"end_time", config.run.end_time}};
      if (scenario.impact) {
        out["target_particles"] = scenario.impact->target_particles;
        out["projectile_particles"] = scenario.impact->projectile_particles;
        out["t_transition"] = scenario.impact->transition_time;
      }
      std::cout << out.dump(2) << "\n";
      return;
    }
    if (scenario.impact) fmt::print("{}", sph::describe_impact(*scenario.impact));
    fmt::print("{} ({}): {} particles ({} fixed), end time {:.6g} s; dry run, nothing simulated or written\n",
               config.name, sph::setup_name(config.setup), p.size(), fixed, config.run.end_time);
    return;
  }
  sph::RunOptions run;
  run.output_directory = options.out;
  run.resume = options.resume;
  run.progress = !options.quiet;
  const auto summary = sph::run_simulation(config, run);
  if (options.json) {
    std::cout << summary_json(summary).dump(2) << "\n";
    return;
  }
  fmt::print("{} ({}): {} particles, {} steps to t = {:.6g} s in {:.3f} s wall on {} threads\n", summary.name,
             summary.setup, summary.particles, summary.steps, summary.time, summary.wall_seconds,
             summary.threads);
  fmt::print("  {:.4g} particle updates/s, {:.1f} neighbours/particle, {:.0f} bytes/particle\n",
             summary.particle_updates_per_second, summary.mean_neighbours, summary.bytes_per_particle);
  if (summary.momentum_conserved) {
    fmt::print("  relative energy error {:.3e}, relative momentum error {:.3e}\n",
               summary.relative_energy_error, summary.relative_momentum_error);
  } else {
    fmt::print(
        "  relative energy error {:.3e}; momentum not conserved here (gravity, fixed particles or mirror\n"
        "  planes act on the particles): it changed by {:.3e} of the particles' momentum\n",
        summary.relative_energy_error, summary.relative_momentum_error);
  }
  if (summary.crater) {
    fmt::print("  crater radius {:.4g} +- {:.2g} m, depth {:.4g} m{}; ejected {} particles ({:.4g} kg)\n",
               summary.crater->crater_radius, summary.crater->crater_radius_uncertainty,
               summary.crater->depth, summary.crater_growth_ended ? " (crater growth ended)" : "",
               summary.ejected_particles, summary.ejected_mass);
    if (!summary.crater_growth_ended && summary.crater_growth_end_time) {
      fmt::print(
          "  crater growth ended at t = {:.6g} s (radius {:.4g} m then); the run went on to t = {:.6g} s\n",
          *summary.crater_growth_end_time, *summary.crater_growth_end_radius, summary.time);
    }
  }
  if (summary.late_stage) {
    fmt::print("  late stage from t = {:.6g} s: largest Mach number {:.4g} at the switch, {:.4g} after\n",
               summary.transition_time, summary.mach_at_transition, summary.late_stage_max_mach);
  }
  if (!summary.checkpoint.empty())
    fmt::print("  output in {} (checkpoint {})\n", options.out, summary.checkpoint);
  fmt::print("{}", summary.phase_table);
}

void add_simulate_command(CLI::App& parent) {
  auto options = std::make_shared<SimulateOptions>();
  auto* sub = parent.add_subcommand("simulate",
                                    "Run an SPH simulation described by a TOML configuration (e.g. "
                                    "data/examples/sedov.toml)");
  sub->add_option("config", options->config, "Configuration file (TOML)")->required();
  sub->add_option("--out", options->out, "Output directory (snapshots, checkpoint.h5, conservation.csv)");
  sub->add_option("--threads", options->threads, "OpenMP threads (default: all cores)");
  sub->add_flag("--resume", options->resume, "Continue from DIR/checkpoint.h5 when it exists");
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

const bool registered = register_command({"simulate", 50, &add_simulate_command});

}  // namespace
}  // namespace craterkit::cli
