#pragma once
// The scenario-independent part of a `craterkit simulate` configuration (keys and defaults in
// docs/simulate.md; examples: data/examples/*.toml). A scenario reads [problem] setup and its own tables
// (run/standard_problems.hpp, impact/impact_config.hpp) and this parser the rest:
//
//   [problem]    name
//   [run]        end_time (s), max_steps (0: no limit), gravity = [gx, gy, gz] (m/s^2)
//   [kernel]     type = "cubic_spline" | "wendland_c2", eta, min_smoothing_length, max_smoothing_length,
//                max_smoothing_ratio, neighbour_band (integration/integrator.hpp),
//                density = "continuity" | "summation" (rates/summation_density.hpp: for gases only)
//   [viscosity]  alpha, beta, switch = "none" | "morris_monaghan", alpha_min, decay_factor, epsilon, balsara
//   [artificial_stress]  epsilon (0: off; Gray et al. 2001 use 0.3): solids only
//   (rates/artificial_stress.hpp) [time_step]  courant, acceleration_factor, density_change, energy_change,
//   energy_floor, max_step,
//                velocity_change, block_levels
//   [neighbours] skin, sort_interval (steps between curve sorts)
//   [output]     snapshot_times = [...] (s), checkpoint_interval_steps, checkpoint_interval_seconds,
//                conservation_log (bool), compression (0: none .. 9: deflate level of the snapshots)
// Every key has a default (the scenario's, see parse_simulation_config); unknown keys, wrong types and
// out-of-range values are craterkit::InputError naming the key, the value and what is allowed.
#include <cstdint>
#include <string>
#include <vector>

#include "craterkit/common/toml_table.hpp"
#include "craterkit/sph/solver/solver_parameters.hpp"

namespace craterkit::sph {

struct RunParameters {
  double end_time = 0.0;        // s (> 0, required)
  std::uint64_t max_steps = 0;  // 0: unlimited
};

struct OutputParameters {
  std::vector<double> snapshot_times;           // s, ascending; the final state is always written too
  std::uint64_t checkpoint_interval_steps = 0;  // 0: none by step count
  double checkpoint_interval_seconds = 600.0;   // wall seconds between checkpoints (0: none)
  bool conservation_log = true;
  int compression = 0;  // deflate level of the snapshots' datasets, 0 (none) .. 9
};

struct SimulationConfig {
  std::string name = "simulation";
  SolverParameters solver{};
  RunParameters run{};
  OutputParameters output{};
};

// Reads [problem] name (problem.setup is the scenario's) and the tables above from `root`, starting from
// the scenario's `defaults`. Two defaults follow from other keys: block_levels is 0 unless the density is
// integrated (block steps need the continuity density; otherwise defaults.block_levels), and the neighbour
// skin is 0.1 with block steps (the lists are checked at every substep; otherwise defaults' skin).
SimulationConfig parse_simulation_config(TomlTable& root, const SimulationConfig& defaults);

// Refuses checkpoints by wall clock without curve sorting (output.checkpoint_interval_seconds > 0 with
// neighbours.sort_interval = 0): InputError naming both keys, prefixed by `where` (e.g. "FILE: ").
// Checkpoints change no result only when they fall after steps after which the engine sorts and rebuilds its
// neighbour search anyway (run_simulation.hpp); without sorts a checkpoint has to force that rebuild, and at
// wall-clock moments the result would depend on the machine's load. parse_simulation_config() and
// run_simulation() call it.
void check_checkpoint_timing(const SimulationConfig& config, const std::string& where);

// The value of [problem] setup, which must be one of `setups`; a table named after another of them is an
// error (it would be ignored).
std::string read_problem_setup(TomlTable& root, const std::vector<std::string>& setups);

}  // namespace craterkit::sph
