#pragma once
// Minimum-image separation along one axis of a periodic box.

namespace craterkit::sph {

// d wrapped into [-half, half] for an axis of the given period; half = +infinity for a non-periodic axis
// (never wraps). The pair loops pass half = period / 2 precomputed.
[[nodiscard, gnu::always_inline]] inline double minimum_image(double d, double period, double half) noexcept {
  if (d > half) return d - period;
  if (d < -half) return d + period;
  return d;
}

}  // namespace craterkit::sph
