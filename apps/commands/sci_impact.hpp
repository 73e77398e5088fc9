#pragma once
// The Hayabusa2 SCI experiment (docs/physics.md sections 4 and 6), against which the report sets the
// engine's craters and the fitted laws: 2 kg of aluminium at 2 km/s, vertical, into Ryugu under
// g = 1.4e-4 m/s^2, and the crater it made.
#include <cmath>
#include <numbers>

#include "craterkit/scaling/point_source.hpp"
#include "craterkit/scaling/radii_table.hpp"

namespace craterkit::cli {

inline constexpr double kSciMass = 2.0;             // kg
inline constexpr double kSciDensity = 2700.0;       // kg/m^3
inline constexpr double kSciVelocity = 2000.0;      // m/s
inline constexpr double kSciGravity = 1.4e-4;       // m/s^2
inline constexpr double kSciObservedRadius = 7.25;  // m, apparent radius (Arakawa et al. 2020)
inline constexpr double kSciObservedSigma = 0.8;    // m

inline scaling::Impactor sci_impactor() {
  return {std::cbrt(3.0 * kSciMass / (4.0 * std::numbers::pi * kSciDensity)), kSciDensity, kSciVelocity};
}

// Whether a table row is the SCI impact (any target): the tables hold the sweep's numbers to 17 digits, so
// a relative tolerance of 1e-9 separates the SCI from every other impact without depending on the last bit.
inline bool is_sci_impact(const scaling::ImpactRecord& row) {
  const auto close = [](double a, double b) { return std::abs(a - b) <= 1e-9 * std::abs(b); };
  const auto sci = sci_impactor();
  return close(row.impactor.radius, sci.radius) && close(row.impactor.density, sci.density) &&
         close(row.impactor.velocity, sci.velocity) && close(row.target.gravity, kSciGravity);
}

}  // namespace craterkit::cli
