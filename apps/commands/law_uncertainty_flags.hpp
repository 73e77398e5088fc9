#pragma once
// Flags and output of the scaling-law uncertainty in `craterkit rates` and `craterkit age`
// (docs/chronology.md, "Scaling-law uncertainty"): with a fitted law that has a covariance (--fit), the
// fitted constants are drawn --samples times (seeded by --seed) from their multivariate normal and every
// reported quantity is computed for each draw; the outputs give its 15.87/50/84.13 percentiles beside the
// central value. Without a covariance (--params, constants as flags, or --samples 0) nothing is drawn and
// the outputs are exactly those of a law without uncertainty.
#include <cstdint>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "craterkit/scaling/law_uncertainty.hpp"
#include "scaling_flags.hpp"

namespace craterkit::cli {

struct LawUncertaintyFlags {
  int samples = 1000;
  std::uint64_t seed = 1;
};

// Adds --samples and --seed.
void add_law_uncertainty_flags(CLI::App& command, LawUncertaintyFlags& flags);

// The draws, or nothing when the law has no covariance or --samples is 0. Checks --samples (InputError);
// writes a warning to stderr when a fit's covariance was dropped or a constant was not determined.
std::optional<scaling::LawSamples> draw_laws(const ScalingInputs& inputs, const LawUncertaintyFlags& flags);

// {"p16": x, "p50": x, "p84": x}, each times `scale`.
nlohmann::json percentiles_json(const scaling::Percentiles& p, double scale = 1.0);

// What was drawn: method, samples, seed, the constants drawn and held, the rejected draws, the percentiles.
nlohmann::json law_uncertainty_json(const ScalingInputs& inputs, const LawUncertaintyFlags& flags,
                                    const scaling::LawSamples& samples);

// The same as one comment line for text outputs ("# scaling-law uncertainty: ...").
std::string law_uncertainty_comment(const ScalingInputs& inputs, const LawUncertaintyFlags& flags,
                                    const scaling::LawSamples& samples);

}  // namespace craterkit::cli
