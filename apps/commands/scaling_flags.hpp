#pragma once
// Command-line flags shared by every command that evaluates the point-source scaling law
// (scale, run, and the chronology commands), and their resolution into a ScalingLaw plus the
// impact and target defaults that came with it.
//
// Usage in a command file:
//   auto flags = std::make_shared<craterkit::cli::ScalingFlags>();
//   craterkit::cli::add_scaling_flags(*sub, *flags);        // --params --fit --group --K1 --K2 --H1 --H2
//   --mu --nu
//                                                          // --gravity --target-density
//                                                          // --impactor-density --velocity
//   craterkit::cli::add_strength_flag(*sub, *flags);        // --strength (optional; a command that sweeps
//                                                          // cohesion may add its own flag instead)
//   sub->callback([flags] {
//     const auto inputs = craterkit::cli::resolve_scaling_flags(*flags);   // throws InputError
//     const double g = craterkit::cli::require_value(inputs.gravity, "--gravity");
//     ...
//   });
//
// Resolution rules (documented in --help and docs/scaling.md):
//  - The law starts from --params NAME (a set in data/scaling/) or --fit FIT.json (written by
//    `craterkit fit --out`); giving both is an error. Without either, the coefficient pair, --mu and
//    --nu are all required. A grouped fit needs --group KEY=VALUE[,KEY=VALUE] to choose one group's law
//    (the error lists the groups); --group is an error without --fit or with a single fit.
//  - A fit's covariance comes with its law (ScalingInputs::covariance) unless a flag below overrides a
//    constant: the covariance then no longer describes the law, and is dropped with a note.
//  - --K1/--K2 select the Holsapple form, --H1/--H2 the Housen & Holsapple (2011) form; mixing the two
//    pairs is an error. When the base law is in the other form it is first converted exactly
//    (K1 = H1, K2 = (H1/H2)^(2/mu), at the base law's mu) and then the given flags override.
//  - --mu, --nu override the base law's exponents.
//  - strength: --strength, else the fit's shared Y, else the set's strength; target density: the flag,
//    else the set's. Gravity, impactor density and velocity come only from flags. Whatever is still
//    unknown stays empty; require_value() turns it into an error naming the flag.
//  - A coefficient the set does not give (ConstantSet::not_given) stays NaN; the law functions report it
//    by name only when an impact needs it.
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "craterkit/scaling/grouped_fit.hpp"
#include "craterkit/scaling/law_uncertainty.hpp"
#include "craterkit/scaling/point_source.hpp"

namespace craterkit::cli {

struct ScalingFlags {
  std::optional<std::string> params;    // --params NAME
  std::optional<std::string> fit_file;  // --fit FIT.json
  std::optional<std::string> group;     // --group KEY=VALUE[,KEY=VALUE] (a group of a grouped fit)
  std::optional<double> K1, K2, H1, H2, mu, nu;
  std::optional<double> gravity;           // --gravity, m/s^2
  std::optional<double> target_density;    // --target-density, kg/m^3
  std::optional<double> impactor_density;  // --impactor-density, kg/m^3
  std::optional<double> velocity;          // --velocity, m/s
  std::optional<double> strength;          // --strength, Pa (only if add_strength_flag was called)
};

// Adds --params --fit --group --K1 --K2 --H1 --H2 --mu --nu --gravity --target-density --impactor-density
// --velocity to `app`, storing into `flags` (which must outlive parsing).
void add_scaling_flags(CLI::App& app, ScalingFlags& flags);

// Adds --strength (Pa).
void add_strength_flag(CLI::App& app, ScalingFlags& flags);

struct ScalingInputs {
  scaling::ScalingLaw law;  // validated where given; coefficients a set does not give are NaN
  std::string law_source;   // "set jutzi2022_ryugu", "fit FIT.json", "fit FIT.json group k=v, ..." or "flags"
  scaling::GroupKey group;  // the group chosen from a grouped fit (empty otherwise)
  scaling::LawCovariance covariance;  // the fit's, for the law as given (none for a set or flags)
  std::string covariance_note;        // why a fit's covariance was dropped, if it was
  std::optional<double> strength;
  std::optional<double> target_density;
  std::optional<double> gravity;
  std::optional<double> impactor_density;
  std::optional<double> velocity;
};

// Applies the rules above; throws craterkit::InputError naming the flag, the value and what is allowed.
ScalingInputs resolve_scaling_flags(const ScalingFlags& flags);

// The law of `inputs` as reported in the JSON output of commands: source, form, coefficients, mu, nu (and
// the group, when one was chosen from a grouped fit).
nlohmann::json scaling_law_json(const ScalingInputs& inputs);

// The value, or InputError "<flag> is required ..." when it is empty.
double require_value(const std::optional<double>& value, const std::string& flag);

}  // namespace craterkit::cli
