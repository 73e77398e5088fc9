#pragma once
// A configuration file for one of the standard test problems (problem.setup = "sedov" | "sod" | "plates";
// examples data/examples/{sedov,sod,plates}.toml; keys in docs/simulate.md): the set-up's table, the
// optional [late_stage] switch, and the scenario-independent tables of io/config.hpp.
//
//   [sedov] / [sod] / [plates]   the set-up parameters (standard_problems.hpp); only the chosen one may
//   appear [late_stage] t_transition (s; 0: none), A_low (Pa): the low-sound-speed switch
//   (physics/late_stage.hpp)
#include <string>
#include <variant>
#include <vector>

#include "craterkit/common/toml_table.hpp"
#include "craterkit/sph/io/config.hpp"
#include "craterkit/sph/run/run_simulation.hpp"
#include "craterkit/sph/run/standard_problems.hpp"

namespace craterkit::sph {

using StandardProblem = std::variant<SedovSetup, SodSetup, PlateImpactSetup>;

struct LateStageParameters {
  double transition_time = 0.0;  // s; 0: no switch
  double A_low = 0.027e6;        // Pa
};

struct StandardProblemConfig {
  SimulationConfig simulation{};
  StandardProblem problem = SedovSetup{};
  LateStageParameters late_stage{};
};

// "sedov", "sod", "plates".
const std::vector<std::string>& standard_problem_names();
[[nodiscard]] std::string setup_name(const StandardProblem& problem);

// Reads a whole configuration whose problem.setup is a standard problem; every table of `root` must be
// read (unknown ones are errors naming them).
StandardProblemConfig parse_standard_problem_config(TomlTable& root);
StandardProblemConfig parse_standard_problem_config(const std::string& toml_text, const std::string& source);

// The problem's particles, materials and box, with its late-stage plan. Fails early (naming the material)
// when a late stage is planned for a law without a bulk modulus, e.g. an ideal gas.
ProblemSetup build_standard_problem(const StandardProblemConfig& config);

// The run record ("setup") and the run of the problem (run_simulation.hpp).
RunAttributes standard_problem_record(const StandardProblemConfig& config);
RunSummary run_standard_problem(const StandardProblemConfig& config, const RunOptions& options);

}  // namespace craterkit::sph
