// Scaling-law uncertainty flags and output (see law_uncertainty_flags.hpp).
#include "law_uncertainty_flags.hpp"

#include <iostream>

#include <fmt/format.h>

#include "craterkit/common/input_error.hpp"
#include "join.hpp"

namespace craterkit::cli {
namespace {

constexpr int kMinSamples = 100;  // fewer draws give percentiles too coarse to report
constexpr int kMaxSamples = 1000000;

}  // namespace

void add_law_uncertainty_flags(CLI::App& command, LawUncertaintyFlags& flags) {
  command
      .add_option("--samples", flags.samples,
                  "Draws of the fitted constants from their covariance (with --fit) for the scaling-law "
                  "uncertainty; 0 turns it off")
      ->capture_default_str();
  command.add_option("--seed", flags.seed, "Seed of the draws (the same seed gives the same draws)")
      ->capture_default_str();
}

std::optional<scaling::LawSamples> draw_laws(const ScalingInputs& inputs, const LawUncertaintyFlags& flags) {
  if (flags.samples != 0 && (flags.samples < kMinSamples || flags.samples > kMaxSamples)) {
    throw InputError(
        fmt::format("--samples {} is not allowed: use 0 (no scaling-law uncertainty) or {} to {}",
                    flags.samples, kMinSamples, kMaxSamples));
  }
  if (!inputs.covariance_note.empty()) std::cerr << "craterkit: warning: " << inputs.covariance_note << "\n";
  if (flags.samples == 0 || !inputs.covariance.has_covariance()) return std::nullopt;
  if (!inputs.covariance.undetermined.empty()) {
    std::cerr
        << "craterkit: warning: " << join(inputs.covariance.undetermined)
        << " not determined by the fit: held at the fitted value, so the scaling-law uncertainty leaves "
           "out its spread\n";
  }
  return scaling::sample_laws(inputs.covariance, flags.samples, flags.seed);
}

nlohmann::json percentiles_json(const scaling::Percentiles& p, double scale) {
  return {{"p16", p.p16 * scale}, {"p50", p.p50 * scale}, {"p84", p.p84 * scale}};
}

nlohmann::json law_uncertainty_json(const ScalingInputs& inputs, const LawUncertaintyFlags& flags,
                                    const scaling::LawSamples& samples) {
  return {{"method",
           "sampling: the fitted constants drawn from their multivariate normal (ln of the coefficients, mu, "
           "nu; truncated to the fit's ranges), every quantity computed per draw"},
          {"samples", flags.samples},
          {"seed", flags.seed},
          {"drawn", inputs.covariance.names},
          {"fixed", inputs.covariance.fixed},
          {"undetermined_held", inputs.covariance.undetermined},
          {"rejected_draws", samples.rejected},
          {"percentiles", {15.87, 50.0, 84.13}}};
}

std::string law_uncertainty_comment(const ScalingInputs& inputs, const LawUncertaintyFlags& flags,
                                    const scaling::LawSamples& samples) {
  std::string held;
  if (!inputs.covariance.fixed.empty()) held += "; fixed " + join(inputs.covariance.fixed);
  if (!inputs.covariance.undetermined.empty())
    held += "; undetermined, held " + join(inputs.covariance.undetermined);
  return fmt::format(
      "# scaling-law uncertainty: 15.87-84.13 % range over {} draws of the fitted {} from their covariance "
      "(seed {}{}{})",
      flags.samples, join(inputs.covariance.names), flags.seed, held,
      samples.rejected > 0 ? fmt::format("; {} draws outside the fit's ranges redrawn", samples.rejected)
                           : "");
}

}  // namespace craterkit::cli
