#include "craterkit/sph/run/run_simulation.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <memory>

#include "craterkit/common/input_error.hpp"
#include "craterkit/common/version.hpp"
#include "craterkit/sph/io/checkpoint.hpp"
#include "craterkit/sph/io/solver_state.hpp"
#include "craterkit/sph/run/progress.hpp"
#include "output_observers.hpp"

namespace craterkit::sph {

namespace {

using Clock = std::chrono::steady_clock;

// The checkpoint of the run: when it is due, and what it holds (the solver's state, the run record and what
// every observer needs to resume).
class Checkpoints {
 public:
  Checkpoints(std::filesystem::path path, const OutputParameters& output, const RunAttributes& record,
              std::span<RunObserver* const> observers)
      : path_(std::move(path)), output_(output), record_(record), observers_(observers) {}

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

  void write_if_due(Simulation& simulation) {
    const auto now = Clock::now();
    const bool by_steps = output_.checkpoint_interval_steps > 0 &&
                          simulation.step_count() % output_.checkpoint_interval_steps == 0;
    const bool by_wall =
        output_.checkpoint_interval_seconds > 0 &&
        std::chrono::duration<double>(now - last_).count() >= output_.checkpoint_interval_seconds;
    if (!by_steps && !by_wall) return;
    write(simulation);
    last_ = now;
  }

  void write(Simulation& simulation) {
    auto scope = simulation.timers().measure("output");
    RunAttributes a = run_attributes(simulation, record_);
    for (const RunObserver* o : observers_) o->save(a);
    write_checkpoint(path_, simulation.particles(), a);
    // A resumed run builds its neighbour lists afresh: so does this one, to follow the same sequence.
    simulation.force_neighbour_rebuild();
  }

 private:
  std::filesystem::path path_;
  const OutputParameters& output_;
  const RunAttributes& record_;
  std::span<RunObserver* const> observers_;
  Clock::time_point last_ = Clock::now();
};

// A Simulation continued from the checkpoint (whose attributes go to *checkpoint).
std::unique_ptr<Simulation> resume_simulation(const SimulationConfig& config, ProblemSetup problem,
                                              const RunAttributes& record, const std::filesystem::path& path,
                                              RunAttributes* checkpoint) {
  Particles particles = read_checkpoint(path, checkpoint);
  const auto setup = checkpoint->texts.find("setup");
  const std::string expected = record.texts.count("setup") != 0 ? record.texts.at("setup") : "?";
  if (setup == checkpoint->texts.end() || setup->second != expected) {
    throw InputError(path.string() + ": checkpoint of a different problem (setup \"" +
                     (setup == checkpoint->texts.end() ? std::string("?") : setup->second) +
                     "\", configuration: \"" + expected + "\")");
  }
  return std::make_unique<Simulation>(config.solver, std::move(problem), std::move(particles),
                                      read_solver_state(*checkpoint, "checkpoint"));
}

void summarise(const Simulation& sim, RunSummary& summary) {
  const auto& p = sim.particles();
  const auto final_state = sim.conserved();
  summary.particles = p.size();
  summary.steps = sim.step_count();
  summary.time = sim.time();
  summary.mean_neighbours = sim.mean_neighbours();
  summary.relative_energy_error = relative_energy_error(sim.initial_conserved(), final_state);
  summary.relative_momentum_error = relative_momentum_error(sim.initial_conserved(), final_state);
  const auto& gravity = sim.parameters().gravity;
  const bool has_fixed =
      std::any_of(p.flags.begin(), p.flags.end(), [](std::uint8_t f) { return (f & particle_fixed) != 0; });
  summary.momentum_conserved =
      gravity[0] == 0.0 && gravity[1] == 0.0 && gravity[2] == 0.0 && !has_fixed && !sim.box().any_mirror();
  summary.bytes_per_particle = sim.bytes_per_particle();
  summary.neighbour_rebuilds = sim.neighbour_rebuilds();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if ((p.flags[i] & particle_ejected) == 0) continue;
    ++summary.ejected_particles;
    summary.ejected_mass += p.mass[i];
  }
  if (sim.problem().late_stage.planned()) {
    summary.transition_time = sim.problem().late_stage.transition_time;
    summary.late_stage = sim.late_stage_active();
    summary.mach_at_transition = sim.mach_at_transition();
    summary.late_stage_max_mach = sim.late_stage_max_mach();
  }
}

}  // namespace

RunSummary run_simulation(const SimulationConfig& config, ProblemSetup problem,
                          const RunAttributes& record_in, const RunOptions& options,
                          std::span<RunObserver* const> scenario_observers) {
  namespace fs = std::filesystem;
  const auto wall_start = Clock::now();
  const bool files = !options.output_directory.empty();
  const fs::path out = options.output_directory;
  if (files) fs::create_directories(out);

  RunAttributes record = record_in;
  record.texts["problem_name"] = config.name;
  record.texts["craterkit_version"] = craterkit::version();
  if (!options.configuration.empty()) record.texts["configuration"] = options.configuration;
  RunSummary summary;
  summary.name = config.name;
  summary.setup = record.texts.count("setup") != 0 ? record.texts.at("setup") : "";
  summary.threads = omp_get_max_threads();

  const bool logs_ejecta = files && problem.ejection.radius > 0.0;
  summary.resumed = files && options.resume && fs::exists(out / "checkpoint.h5");
  RunAttributes checkpoint_attributes;
  auto sim = summary.resumed ? resume_simulation(config, std::move(problem), record, out / "checkpoint.h5",
                                                 &checkpoint_attributes)
                             : std::make_unique<Simulation>(config.solver, std::move(problem));

  // The observers, in the order they act after a step.
  LateStageReport late_stage_report;
  EjectaLog ejecta_log(out / "ejecta.csv");
  ConservationRecorder conservation(out / "conservation.csv");
  SnapshotWriter snapshots(out, config.output.snapshot_times, record, config.output.compression);
  std::vector<RunObserver*> observers;
  if (options.log) observers.push_back(&late_stage_report);
  if (logs_ejecta) observers.push_back(&ejecta_log);
  if (files && config.output.conservation_log) observers.push_back(&conservation);
  if (files) observers.push_back(&snapshots);
  observers.insert(observers.end(), scenario_observers.begin(), scenario_observers.end());
  Checkpoints checkpoints(out / "checkpoint.h5", config.output, record, observers);

  ProgressOptions progress_options;
  progress_options.enabled = options.progress;
  progress_options.end_time = config.run.end_time;
  if (sim->problem().late_stage.planned())
    progress_options.stage_end_time = sim->problem().late_stage.transition_time;
  Progress progress(progress_options);

  const RunAttributes* resumed_from = summary.resumed ? &checkpoint_attributes : nullptr;
  bool ended = false;
  for (RunObserver* o : observers) ended = o->start(*sim, resumed_from) || ended;
  const std::uint64_t first_step = sim->step_count();
  const std::uint64_t first_updates = sim->particle_updates();
  while (!ended && sim->time() < config.run.end_time &&
         (config.run.max_steps == 0 || sim->step_count() < config.run.max_steps)) {
    double target = config.run.end_time;
    for (const RunObserver* o : observers) target = std::min(target, o->next_landing_time());
    sim->step(target);
    if (!logs_ejecta) (void)sim->take_new_ejecta();  // nobody logs them
    for (RunObserver* o : observers) ended = o->after_step(*sim) || ended;
    if (files) checkpoints.write_if_due(*sim);
    progress.update(sim->time(), sim->step_count(), sim->next_time_step(), sim->particle_updates());
  }
  progress.finish(sim->time(), sim->step_count(), sim->next_time_step(), sim->particle_updates());
  summary.ended_by_observer = ended;

  // The final state: a snapshot and a checkpoint, so that --resume of a finished run does nothing and a
  // longer end_time continues it; then the scenario's conclusions (e.g. the crater).
  for (RunObserver* o : observers) o->finish(*sim);
  if (files) {
    checkpoints.write(*sim);
    summary.checkpoint = checkpoints.path().string();
    summary.snapshots = snapshots.written();
    if (config.output.conservation_log) summary.conservation_log = conservation.path().string();
    if (logs_ejecta) summary.ejecta_log = ejecta_log.path().string();
  }
  summarise(*sim, summary);
  summary.steps_this_run = sim->step_count() - first_step;
  summary.wall_seconds = std::chrono::duration<double>(Clock::now() - wall_start).count();
  summary.particle_updates = sim->particle_updates() - first_updates;
  summary.particle_updates_per_second =
      summary.wall_seconds > 0 ? static_cast<double>(summary.particle_updates) / summary.wall_seconds : 0.0;
  auto& timers = sim->timers();
  summary.phase_seconds = timers.seconds_by_phase();
  summary.phase_table = timers.table();
  return summary;
}

}  // namespace craterkit::sph
