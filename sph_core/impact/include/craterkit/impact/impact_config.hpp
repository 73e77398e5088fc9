#pragma once
// A configuration file for an impact (problem.setup = "impact"; examples data/examples/sci*.toml,
// impact-*.toml; keys, defaults and ranges in docs/impact_setup.md and docs/simulate.md):
//
//   [impact]     the impact set-up (impact_setup.hpp), with its [[impact.boulders]] array (a boulder's keys
//                as impact.boulders[<i>].<key>, its parts as impact.boulders[<i>].parts[<j>].<key>)
//   [crater]     the end of crater growth (crater_growth.hpp: check_interval, radius_tolerance,
//                kinetic_energy_fraction, window_fraction, stop_when_grown)
//   and the scenario-independent tables of sph/io/config.hpp, whose defaults an impact changes
//   (impact_simulation_defaults()).
// Unknown keys, wrong types and out-of-range values are craterkit::InputError "<source>: impact.<key>: ...".
#include <filesystem>
#include <string>

#include "craterkit/common/toml_table.hpp"
#include "craterkit/impact/crater_growth.hpp"
#include "craterkit/impact/impact_setup.hpp"
#include "craterkit/sph/io/config.hpp"

namespace craterkit::impact {

// The solver defaults of an impact (docs/simulate.md, "Defaults for impacts"):
//  - h at most 3 eta (m/rho)^(1/3) per particle (kernel.max_smoothing_ratio): a particle thrown clear of the
//    target (the ejecta curtain before it leaves the domain) has too few neighbours, and the neighbour-count
//    correction would otherwise grow its h without bound, until the neighbour search and the crater
//    measurement visit every particle for it;
//  - the Morris-Monaghan viscosity switch with the Balsara limiter: with a constant alpha = 1 the viscosity
//    damps the excavation flow behind the shock within about a millisecond and the crater stays small
//    (docs/validation.md, "Impact craters");
//  - the energy-change limit with u_floor = U^2/400 (1e4 J/kg at 2 km/s) and the velocity-change limit 0.1
//    (integration/time_step.hpp): without them the light stand-in projectile's specific energy can change
//    sign within one step;
//  - block time steps with 8 levels: the finest particles of a graded target step up to 256 times per step
//    of the coarsest.
sph::SimulationConfig impact_simulation_defaults(const ImpactSetup& impact);

struct ImpactConfig {
  sph::SimulationConfig simulation = impact_simulation_defaults(ImpactSetup{});
  ImpactSetup impact{};
  CraterGrowthParameters crater{};
};

// The [impact] table alone.
ImpactSetup parse_impact_setup(TomlTable impact);

// A whole configuration whose problem.setup is "impact"; every table of `root` must be read.
ImpactConfig parse_impact_config(TomlTable& root);
ImpactConfig parse_impact_config(const std::string& toml_text, const std::string& source);
ImpactConfig load_impact_config(const std::filesystem::path& path);

}  // namespace craterkit::impact
