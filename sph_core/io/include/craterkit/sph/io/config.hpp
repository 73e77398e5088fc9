#pragma once
// The TOML configuration of `craterkit simulate` (examples: data/examples/*.toml). Every key has a
// default (the struct initialisers below); unknown keys, wrong types and out-of-range values are
// craterkit::InputError naming the key, the value and what is allowed.
//
//   [problem]    name, setup = "sedov" | "sod" | "plates" | "impact"
//   [sedov] / [sod] / [plates]   the set-up parameters (setups.hpp); only the chosen one may appear
//   [impact]     the impact set-up (impact_config.hpp, docs/impact_setup.md)
//   [late_stage] t_transition (s), A_low (Pa): the low-sound-speed switch for non-impact problems (an
//                impact takes them from impact.t_transition and impact.A_low)
//   [crater]     impact only: end of crater growth (check_interval, radius_tolerance,
//                kinetic_energy_fraction, window_fraction, stop_when_grown; docs/crater_measurement.md)
//   [run]        end_time (s), max_steps (0: no limit), gravity = [gx, gy, gz] (m/s^2)
//   [kernel]     type = "cubic_spline" | "wendland_c2", eta, min_smoothing_length, max_smoothing_length,
//                neighbour_band (integrator.hpp), density = "continuity" | "summation"
//                (summation_density.hpp: for gases only)
//   [viscosity]  alpha, beta, switch = "none" | "morris_monaghan", alpha_min, decay_factor, epsilon
//   [artificial_stress]  epsilon (0: off; Gray et al. 2001 use 0.3): solids only (artificial_stress.hpp)
//   [time_step]  courant, acceleration_factor, density_change, energy_change, energy_floor, max_step
//   [neighbours] skin, sort_interval (steps between curve sorts)
//   [output]     snapshot_times = [...] (s), checkpoint_interval_steps, checkpoint_interval_seconds,
//                conservation_log (bool)
#include <cstdint>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include "craterkit/impact/impact_setup.hpp"
#include "craterkit/sph/integration/integrator.hpp"
#include "craterkit/sph/neighbours/neighbour_search.hpp"
#include "craterkit/sph/rates/rates.hpp"
#include "craterkit/sph/run/setups.hpp"
#include "craterkit/sph/rates/summation_density.hpp"
#include "craterkit/sph/integration/time_step.hpp"

namespace craterkit::sph {

struct RunParameters {
  double end_time = 0.0;        // s (> 0, required)
  std::uint64_t max_steps = 0;  // 0: unlimited
  std::array<double, 3> gravity{0.0, 0.0, 0.0};
};

struct OutputParameters {
  std::vector<double> snapshot_times;           // s, ascending; the final state is always written too
  std::uint64_t checkpoint_interval_steps = 0;  // 0: none by step count
  double checkpoint_interval_seconds = 600.0;   // wall seconds between checkpoints (0: none)
  bool conservation_log = true;
};

struct NeighbourParameters {
  NeighbourSearchOptions search{};
  std::uint64_t sort_interval = 20;  // steps between space-filling-curve sorts (0: never)
};

// The late-stage switch of a non-impact problem (late_stage.hpp); t_transition = 0: none.
struct LateStageParameters {
  double transition_time = 0.0;  // s
  double A_low = 0.027e6;        // Pa
};

// When crater growth has ended (impact runs; crater_growth.hpp): the crater is measured every
// check_interval of simulated time, and the run stops once, over the last window_fraction of the elapsed
// time, the measured radius stayed within radius_tolerance (relative) and the kinetic energy of the moving
// particles stayed below kinetic_energy_fraction of its peak.
struct CraterParameters {
  double check_interval = 0.0;  // s; 0: end_time / 200
  double radius_tolerance = 0.01;
  double kinetic_energy_fraction = 1e-3;
  double window_fraction = 0.2;
  bool stop_when_grown = true;
};

using SetupParameters = std::variant<SedovSetup, SodSetup, PlateImpactSetup, ImpactSetup>;

struct SimulationConfig {
  std::string name = "simulation";
  SetupParameters setup = SedovSetup{};
  RunParameters run{};
  KernelType kernel = KernelType::cubic_spline;
  DensityMethod density = DensityMethod::continuity;
  SmoothingLengthParameters smoothing{};
  ArtificialViscosity viscosity{};
  double artificial_stress = 0.0;  // epsilon of artificial_stress.hpp; 0: off
  TimeStepParameters time_step{};
  NeighbourParameters neighbours{};
  OutputParameters output{};
  LateStageParameters late_stage{};
  CraterParameters crater{};
};

// Parses TOML text; `source` names the file in error messages.
SimulationConfig parse_simulation_config(const std::string& toml_text, const std::string& source);
// Reads and parses a file (InputError if it cannot be read).
SimulationConfig load_simulation_config(const std::filesystem::path& path);

[[nodiscard]] std::string setup_name(const SetupParameters& setup);

}  // namespace craterkit::sph
