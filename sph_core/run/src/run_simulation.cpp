#include "craterkit/sph/run/run_simulation.hpp"

#include <omp.h>

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <sstream>

#include "craterkit/common/input_error.hpp"
#include "craterkit/common/version.hpp"
#include "craterkit/sph/io/checkpoint.hpp"
#include "craterkit/sph/io/solver_state.hpp"
#include "craterkit/sph/run/progress.hpp"
#include "craterkit/sph/run/thread_share.hpp"
#include "output_observers.hpp"

namespace craterkit::sph {

namespace {

using Clock = std::chrono::steady_clock;

// The checkpoint of the run: when it is due, and what it holds (the solver's state, the run record and what
// every observer needs to resume).
//
// When: a checkpoint must not change the run. The neighbour lists depend on the search built at the last
// restructure, and a resumed run builds its search afresh; a checkpoint after a step whose successor does not
// rebuild would therefore need a rebuild that the run without it does not make (different sum orders, other
// last bits). So with curve sorting on (sort_interval > 0) checkpoints are written only after the steps after
// which the engine sorts and rebuilds anyway (Simulation::next_step_sorts()): by step count every
// checkpoint_interval_steps rounded up to a multiple of sort_interval, and by wall clock at the first such
// step after the interval has passed. Whether or when checkpoints are written then changes no result. Without
// sorting a checkpoint forces the rebuild (results then depend on the step-counted checkpoints' steps; wall-
// clock checkpoints are refused then, check_checkpoint_timing() in io/config.hpp).
class Checkpoints {
 public:
  Checkpoints(std::filesystem::path path, const OutputParameters& output, std::uint64_t sort_interval,
              const RunAttributes& record, std::span<RunObserver* const> observers)
      : path_(std::move(path)),
        output_(output),
        step_interval_(rounded_up(output.checkpoint_interval_steps, sort_interval)),
        record_(record),
        observers_(observers) {}

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

  // True when a checkpoint was written.
  bool write_if_due(Simulation& simulation) {
    // Over several processes the clocks differ: due when due on any, so that all write it together.
    if (output_.checkpoint_interval_seconds > 0 &&
        simulation.any_process(std::chrono::duration<double>(Clock::now() - last_).count() >=
                               output_.checkpoint_interval_seconds)) {
      wall_clock_due_ = true;
    }
    const bool by_steps = step_interval_ > 0 && simulation.step_count() % step_interval_ == 0;
    const bool by_wall = wall_clock_due_ && simulation.next_step_sorts();
    if (!by_steps && !by_wall) return false;
    write(simulation);
    return true;
  }

  // Also the final checkpoint, at whatever step the run ends: a resume from it continues only when the run
  // is extended (end_time, max_steps), and is then exact when that step is one after which the next sorts.
  void write(Simulation& simulation) {
    auto scope = simulation.timers().measure("output");
    RunAttributes a = run_attributes(simulation, record_);
    for (const RunObserver* o : observers_) o->save(a);
    Particles gathered;
    const Particles& whole = simulation.whole_particles(gathered);
    if (simulation.writes_output()) write_checkpoint(path_, whole, a);
    // A resumed run builds its neighbour lists afresh: so does this one, to follow the same sequence (the
    // next step's sort does that anyway when it comes).
    if (!simulation.next_step_sorts()) simulation.force_neighbour_rebuild();
    last_ = Clock::now();
    wall_clock_due_ = false;
  }

 private:
  // n rounded up to a multiple of m (n when m is 0).
  static std::uint64_t rounded_up(std::uint64_t n, std::uint64_t m) {
    return m == 0 ? n : (n + m - 1) / m * m;
  }

  std::filesystem::path path_;
  const OutputParameters& output_;
  std::uint64_t step_interval_;
  const RunAttributes& record_;
  std::span<RunObserver* const> observers_;
  Clock::time_point last_ = Clock::now();
  bool wall_clock_due_ = false;
};

std::map<std::string, std::string> configuration_values(const std::string& listing) {
  std::map<std::string, std::string> values;
  std::istringstream in(listing);
  std::string line;
  while (std::getline(in, line)) {
    const auto eq = line.find(" = ");
    if (eq != std::string::npos) values[line.substr(0, eq)] = line.substr(eq + 3);
  }
  return values;
}

// Refuses a resume whose configuration differs from the checkpoint's in a key that changes the result.
void check_resumed_configuration(const std::filesystem::path& path, const RunAttributes& checkpoint,
                                 const std::string& configuration) {
  if (configuration.empty()) return;
  const auto stored = checkpoint.texts.find("configuration");
  if (stored == checkpoint.texts.end()) return;  // a checkpoint written before configurations were stored
  const std::string difference = resume_configuration_difference(stored->second, configuration);
  if (difference.empty()) return;
  throw InputError("--resume: the configuration differs from the one of checkpoint " + path.string() +
                   " in " + difference +
                   " in the checkpoint; a resumed run may change only run.end_time, run.max_steps, "
                   "problem.name, [output] and neighbours.halo_skin. Resume with the checkpoint's "
                   "configuration, or start the changed run in another --out folder");
}

// The material files of a problem, one line "<index> <hash> <file>" per material read from a file: the run
// record's text "material_files", against which a resume checks that no material file changed.
std::string material_files(const ProblemSetup& problem) {
  std::string lines;
  for (std::size_t i = 0; i < problem.materials.size(); ++i) {
    const Material& m = problem.materials[i];
    if (m.source_file.empty()) continue;
    lines += std::to_string(i) + " " + m.source_hash + " " + m.source_file + "\n";
  }
  return lines;
}

// Refuses a resume when a material file of the checkpoint's run has other contents now: the configuration
// names the material, not its values, and a changed file would continue the run with other physics.
void check_resumed_material_files(const std::filesystem::path& path, const RunAttributes& checkpoint,
                                  const std::string& now) {
  const auto stored = checkpoint.texts.find("material_files");
  if (stored == checkpoint.texts.end()) return;  // a checkpoint written before material files were recorded
  const auto by_index = [](const std::string& text) {
    std::map<std::string, std::pair<std::string, std::string>> out;  // index -> (hash, file)
    std::istringstream in(text);
    std::string index, hash, file;
    while (in >> index >> hash && std::getline(in >> std::ws, file)) out[index] = {hash, file};
    return out;
  };
  const auto then = by_index(stored->second);
  for (const auto& [index, current] : by_index(now)) {
    const auto old = then.find(index);
    if (old == then.end() || old->second.first == current.first) continue;
    const bool moved = old->second.second != current.second;
    throw InputError(
        "--resume: material file " + current.second + " has changed since checkpoint " + path.string() +
        " was written" + (moved ? " (from " + old->second.second + " then)" : std::string()) + ": hash " +
        current.first + " now, " + old->second.first +
        " in the checkpoint. A resumed run must use the material values it started with: restore "
        "the file, or start the changed run in another --out folder");
  }
}

// Removes the temporary files that killed runs left in the output folder (".<name>.tmp.<pid>" of a
// process that no longer runs).
void remove_stale_temporaries(const std::filesystem::path& directory) {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(directory, ec)) {
    const std::string name = entry.path().filename().string();
    const auto mark = name.rfind(".tmp.");
    if (name.empty() || name[0] != '.' || mark == std::string::npos) continue;
    const std::string pid_text = name.substr(mark + 5);
    if (pid_text.empty() || pid_text.find_first_not_of("0123456789") != std::string::npos) continue;
    const long pid = std::strtol(pid_text.c_str(), nullptr, 10);
    const bool alive =
        pid > 0 && pid != ::getpid() && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM);
    if (!alive) std::filesystem::remove(entry.path(), ec);
  }
}

// A Simulation continued from the checkpoint (whose attributes go to *checkpoint).
std::unique_ptr<Simulation> resume_simulation(const SimulationConfig& config, ProblemSetup problem,
                                              const RunAttributes& record, const std::filesystem::path& path,
                                              const std::string& configuration, RunAttributes* checkpoint,
                                              Decomposition* decomposition) {
  Particles particles = read_checkpoint(path, checkpoint);
  const auto setup = checkpoint->texts.find("setup");
  const std::string expected = record.texts.count("setup") != 0 ? record.texts.at("setup") : "?";
  if (setup == checkpoint->texts.end() || setup->second != expected) {
    throw InputError(path.string() + ": checkpoint of a different problem (setup \"" +
                     (setup == checkpoint->texts.end() ? std::string("?") : setup->second) +
                     "\", configuration: \"" + expected + "\")");
  }
  check_resumed_configuration(path, *checkpoint, configuration);
  check_resumed_material_files(path, *checkpoint, material_files(problem));
  try {
    return std::make_unique<Simulation>(config.solver, std::move(problem), std::move(particles),
                                        read_solver_state(*checkpoint, "checkpoint"), decomposition);
  } catch (const std::invalid_argument& e) {
    throw InputError(path.string() + ": the checkpoint's particles cannot be continued: " + e.what());
  }
}

// Fewer threads while other programs keep this run's threads waiting for a processor (thread_share.hpp).
void share_processors(ThreadShare& share, double wall_seconds, const RunOptions& options) {
  if (!share.due(wall_seconds)) return;
  const auto waiting = process_waiting_seconds();
  if (!waiting) return;
  const ThreadShare::Decision decision = share.observe(wall_seconds, *waiting);
  if (decision.threads) omp_set_num_threads(*decision.threads);
  if (options.log && !decision.note.empty()) std::fprintf(stderr, "%s\n", decision.note.c_str());
}

void summarise(const Simulation& sim, RunSummary& summary) {
  const auto& p = sim.particles();
  const auto final_state = sim.conserved();
  summary.particles = sim.total_particles();
  summary.steps = sim.step_count();
  summary.time = sim.time();
  summary.mean_neighbours = sim.mean_neighbours();
  summary.relative_energy_error = relative_energy_error(sim.initial_conserved(), final_state);
  summary.relative_momentum_error = relative_momentum_error(sim.initial_conserved(), final_state);
  const auto& gravity = sim.parameters().gravity;
  const bool has_fixed = sim.any_process(
      std::any_of(p.flags.begin(), p.flags.end(), [](std::uint8_t f) { return (f & particle_fixed) != 0; }));
  summary.momentum_conserved =
      gravity[0] == 0.0 && gravity[1] == 0.0 && gravity[2] == 0.0 && !has_fixed && !sim.box().any_mirror();
  summary.memory_use = sim.memory_use();
  summary.neighbour_rebuilds = sim.neighbour_rebuilds();
  summary.halos_found_anew = sim.halos_found_anew();
  const EjectedTotals ejected = sim.ejected_totals();
  summary.ejected_particles = ejected.particles;
  summary.ejected_mass = ejected.mass;
  if (sim.problem().late_stage.planned()) {
    summary.transition_time = sim.problem().late_stage.transition_time;
    summary.late_stage = sim.late_stage_active();
    summary.mach_at_transition = sim.mach_at_transition();
    summary.late_stage_max_mach = sim.late_stage_max_mach();
  }
}

}  // namespace

bool resumable_configuration_key(const std::string& key) {
  return key == "run.end_time" || key == "run.max_steps" || key == "problem.name" ||
         key == "neighbours.halo_skin" || key.rfind("output.", 0) == 0;
}

std::string resume_configuration_difference(const std::string& checkpoint_listing,
                                            const std::string& current_listing) {
  const auto then = configuration_values(checkpoint_listing);
  const auto now = configuration_values(current_listing);
  // A key that one side did not read (added to or removed from the engine between the two) matches when it is
  // absent from the file on the other side: a new key's default keeps the behaviour from before it existed.
  const std::string absent = "(absent)";
  const std::string not_read = "(not read)";
  auto describe = [](const std::string& key, const std::string& here, const std::string& there) {
    return key + ": " + here + " now, " + there;
  };
  for (const auto& [key, value] : now) {
    if (resumable_configuration_key(key)) continue;
    const auto old = then.find(key);
    if (old == then.end()) {
      if (value != absent) return describe(key, value, not_read);
    } else if (old->second != value) {
      return describe(key, value, old->second);
    }
  }
  for (const auto& [key, value] : then) {
    if (!resumable_configuration_key(key) && value != absent && now.count(key) == 0)
      return describe(key, not_read, value);
  }
  return {};
}

RunSummary run_simulation(const SimulationConfig& config, ProblemSetup problem,
                          const RunAttributes& record_in, const RunOptions& options,
                          std::span<RunObserver* const> scenario_observers) {
  namespace fs = std::filesystem;
  const auto wall_start = Clock::now();
  const bool files = !options.output_directory.empty();
  const fs::path out = options.output_directory;
  if (files) check_checkpoint_timing(config, "");
  const bool writer = options.decomposition == nullptr || options.decomposition->rank() == 0;
  if (files && writer) {
    fs::create_directories(out);
    remove_stale_temporaries(out);
  }

  RunAttributes record = record_in;
  record.texts["problem_name"] = config.name;
  record.texts["craterkit_version"] = craterkit::version();
  if (!options.configuration.empty()) record.texts["configuration"] = options.configuration;
  if (const std::string listed = material_files(problem); !listed.empty())
    record.texts["material_files"] = listed;
  RunSummary summary;
  summary.name = config.name;
  summary.setup = record.texts.count("setup") != 0 ? record.texts.at("setup") : "";
  summary.threads = omp_get_max_threads();
  summary.processes = options.decomposition != nullptr ? options.decomposition->size() : 1;

  const bool logs_ejecta = files && problem.ejection.radius > 0.0;
  summary.resumed = files && options.resume && fs::exists(out / "checkpoint.h5");
  RunAttributes checkpoint_attributes;
  auto sim = summary.resumed
                 ? resume_simulation(config, std::move(problem), record, out / "checkpoint.h5",
                                     options.configuration, &checkpoint_attributes, options.decomposition)
                 : std::make_unique<Simulation>(config.solver, std::move(problem), options.decomposition);

  // The observers, in the order they act after a step.
  LateStageReport late_stage_report;
  EjectaLog ejecta_log(out / "ejecta.csv");
  ConservationRecorder conservation(out / "conservation.csv");
  SnapshotWriter snapshots(out, config.output.snapshot_times, record, config.output.compression);
  std::vector<RunObserver*> observers;
  if (options.log && writer) observers.push_back(&late_stage_report);
  if (logs_ejecta) observers.push_back(&ejecta_log);
  if (files && config.output.conservation_log) observers.push_back(&conservation);
  if (files) observers.push_back(&snapshots);
  observers.insert(observers.end(), scenario_observers.begin(), scenario_observers.end());
  Checkpoints checkpoints(out / "checkpoint.h5", config.output, config.solver.neighbours.sort_interval,
                          record, observers);

  ProgressOptions progress_options;
  progress_options.enabled = options.progress && writer;
  progress_options.end_time = config.run.end_time;
  if (sim->problem().late_stage.planned())
    progress_options.stage_end_time = sim->problem().late_stage.transition_time;
  Progress progress(progress_options);

  ThreadShare thread_share(ThreadShareOptions{.max_threads = summary.threads});
  struct RestoreThreads {  // the next run in this process starts with the count this one was given
    int threads;
    ~RestoreThreads() { omp_set_num_threads(threads); }
  } restore_threads{summary.threads};
  const auto wall_seconds = [&wall_start] {
    return std::chrono::duration<double>(Clock::now() - wall_start).count();
  };
  share_processors(thread_share, wall_seconds(), options);  // the first window starts here
  sim->set_between_substeps([&] { share_processors(thread_share, wall_seconds(), options); });
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
    if (files && checkpoints.write_if_due(*sim) && options.after_checkpoint)
      options.after_checkpoint(sim->step_count());
    // Over several processes: process 0's updates times the processes (the split gives each the same work).
    progress.update(sim->time(), sim->step_count(), sim->next_time_step(),
                    sim->particle_updates() * std::uint64_t(summary.processes));
    share_processors(thread_share, wall_seconds(), options);
  }
  progress.finish(sim->time(), sim->step_count(), sim->next_time_step(),
                  sim->particle_updates() * std::uint64_t(summary.processes));
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
  if (options.decomposition != nullptr) {
    std::array<double, 1> updates{static_cast<double>(summary.particle_updates)};
    options.decomposition->sum(updates);  // every process's
    summary.particle_updates = static_cast<std::uint64_t>(updates[0]);
  }
  summary.particle_updates_per_second =
      summary.wall_seconds > 0 ? static_cast<double>(summary.particle_updates) / summary.wall_seconds : 0.0;
  auto& timers = sim->timers();
  summary.phase_seconds = timers.seconds_by_phase();
  summary.phase_table = timers.table();
  return summary;
}

}  // namespace craterkit::sph
