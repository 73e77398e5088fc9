#pragma once
// Flags shared by `craterkit rates` and `craterkit age`: the target body, its collision environment and
// the conventions that turn scaling-law radii into counted diameters (docs/physics.md section 7), resolved
// into the chronology library's production set-up. The scaling constants themselves come from
// scaling_flags.hpp; --velocity there (one speed) and --speed-table here (a distribution) exclude each other.
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "craterkit/chronology/body.hpp"
#include "craterkit/chronology/conventions.hpp"
#include "craterkit/chronology/population.hpp"
#include "craterkit/chronology/production.hpp"
#include "scaling_flags.hpp"

namespace craterkit::cli {

struct ProductionFlags {
  std::string body = "ryugu";
  std::string region = "main_belt";
  double rim_to_apparent = chronology::DiameterConvention{}.rim_to_apparent;
  std::string cross_section = "target+impactor";
  std::optional<std::string> speed_table;
  double impactor_density = 2600.0;  // kg/m^3, when neither --impactor-density nor the constant set gives one
};

// Adds --body, --region, --rim-to-apparent, --cross-section, --speed-table.
void add_production_flags(CLI::App& command, ProductionFlags& flags);

// Checks the flags (InputError naming the flag) and builds the production set-up for `population`.
chronology::ProductionSetup resolve_production_flags(const ProductionFlags& flags,
                                                     const ScalingFlags& scaling,
                                                     const chronology::Body& body,
                                                     const chronology::ImpactorPopulation& population);

// Checks --cohesion: at least one value, each finite and >= 0 Pa.
void check_cohesions(const std::vector<double>& cohesions);

}  // namespace craterkit::cli
