#pragma once
// The run loop: steps a Simulation from t = 0 (or from the checkpoint of an earlier run) to the end time,
// with the outputs around the steps (docs/output.md):
//  - snapshots (HDF5 + XDMF) at the requested times, which the steps land on exactly, and of the final state;
//  - the conserved-quantities log (conservation.csv) and, when particles can be ejected, ejecta.csv;
//  - a checkpoint (atomically replaced) every N steps or wall seconds and at the end, holding the solver's
//    state, the run record and what each observer needs to resume; the periodic ones only after steps
//    after which the engine sorts and rebuilds its neighbour search anyway, so that checkpoints change no
//    result (N rounded up to a multiple of the sort interval, a due wall-clock one deferred to such a step);
//  - the progress line and the late-stage messages on stderr;
// plus the scenario's own observers (run_observer.hpp), e.g. the impact's crater growth and measurement.
// Per step: step -> built-in observers (late-stage log, ejecta log, conservation log, snapshots) ->
// scenario observers -> checkpoint if due -> progress. The run ends at config.run.end_time, after
// config.run.max_steps, or when an observer says so.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "craterkit/sph/io/config.hpp"
#include "craterkit/sph/io/snapshot.hpp"
#include "craterkit/sph/run/run_observer.hpp"
#include "craterkit/sph/solver/memory_use.hpp"
#include "craterkit/sph/solver/problem.hpp"

namespace craterkit::sph {

struct RunOptions {
  std::filesystem::path output_directory;  // empty: run without writing files
  bool resume = false;                     // continue from output_directory/checkpoint.h5 if present
  bool progress = true;                    // the progress line on stderr
  bool log = true;                         // late-stage messages on stderr
  // The configuration's values as "key = value" lines (TomlTable::values_read()), written into every
  // checkpoint and snapshot as the text attribute "configuration". A resume compares it with the
  // checkpoint's and refuses (InputError naming the key and both values) a difference in any key but
  // resumable_configuration_key()s; empty: no comparison.
  std::string configuration;
  // A run over several processes (solver/decomposition.hpp, docs/parallel.md): every process calls
  // run_simulation() with the same arguments and this process's decomposition (which must outlive the call).
  // The steps run distributed; process 0 writes every file (snapshots and checkpoints of the whole particle
  // set, gathered to it, as a serial run writes them) and the progress line, and a checkpoint resumes on any
  // number of processes. The output folder must be visible to every process (checkpoints are read by all).
  Decomposition* decomposition = nullptr;
  // Called after each checkpoint written during the steps (not the final one) is on disk, with its step.
  std::function<void(std::uint64_t step)> after_checkpoint;
};

// Keys a resumed run may change: run.end_time, run.max_steps, problem.name, [output] and
// neighbours.halo_skin (which halos a process holds, not what it computes).
bool resumable_configuration_key(const std::string& key);

// The first key in which two configuration listings ("key = value" lines, RunOptions::configuration) differ
// in a way a resume may not, as "<key>: <value now> now, <value in the checkpoint>" ("(not read)" for a key
// one side does not know); empty when they agree. A key only one side read agrees when the other side's file
// leaves it out ("(absent)"): the default of a key added to the engine keeps the behaviour from before it.
std::string resume_configuration_difference(const std::string& checkpoint_listing,
                                            const std::string& current_listing);

struct RunSummary {
  std::string name;
  std::string setup;
  std::size_t particles = 0;
  std::uint64_t steps = 0;           // completed steps of the run (including before a restart)
  std::uint64_t steps_this_run = 0;  // steps taken by this invocation
  double time = 0.0;                 // s, simulated
  double wall_seconds = 0.0;
  double particle_updates_per_second = 0.0;  // particle updates of this run / wall_seconds (particles x
                                             // steps with a global step; Simulation::particle_updates())
  std::uint64_t particle_updates = 0;        // of this run (over all processes)
  double mean_neighbours = 0.0;
  double relative_energy_error = 0.0;
  double relative_momentum_error = 0.0;
  // False when external forces act on the particles - gravity, fixed (boundary) particles, mirror planes -
  // so that total momentum is not conserved: relative_momentum_error is then the momentum they took up
  // (for an impact into a target held by its shell, about the projectile's), not an error of the scheme.
  bool momentum_conserved = true;
  MemoryUse memory_use;  // bytes per particle by part; memory_use.total() is Simulation::bytes_per_particle
  int threads = 1;       // OpenMP threads per process
  int processes = 1;     // MPI processes (RunOptions::decomposition)
  bool resumed = false;
  bool ended_by_observer = false;  // an observer ended the run (else end_time or max_steps)
  std::uint64_t neighbour_rebuilds = 0;
  std::uint64_t halos_found_anew = 0;  // distributed block steps, process 0 (Simulation::halos_found_anew)
  std::vector<std::pair<std::string, double>> phase_seconds;
  std::vector<std::string> snapshots;  // files written by this invocation
  std::string checkpoint;              // the last checkpoint written ("" if none)
  std::string conservation_log;
  std::string phase_table;  // PhaseTimers::table()
  // Late stage (when planned).
  bool late_stage = false;           // the switch happened
  double transition_time = 0.0;      // s
  double mach_at_transition = 0.0;   // max |v|/c just after the switch
  double late_stage_max_mach = 0.0;  // max |v|/c over the late stage
  // Ejection (when the problem ejects particles).
  std::size_t ejected_particles = 0;
  double ejected_mass = 0.0;  // kg (in this domain)
  std::string ejecta_log;
};

// record: the constant attributes of the run, written into every snapshot and checkpoint; its text
// "setup" names the scenario, and a checkpoint of another scenario is refused on resume. The problem
// name (config.name) is added as the text "problem_name". A resumed run rebuilds `problem` for its
// materials and box and takes the particles from the checkpoint.
RunSummary run_simulation(const SimulationConfig& config, ProblemSetup problem, const RunAttributes& record,
                          const RunOptions& options, std::span<RunObserver* const> observers = {});

}  // namespace craterkit::sph
