#pragma once
// The cube root of a ratio close to one: the factor (rho_old / rho_new)^(1/3) by which every drift and
// correction rescales h (docs/physics.md, section 1.3). Over one substep the density changes by
// far less than a thousandth almost everywhere, where the binomial series
//   (1 + e)^(1/3) = 1 + e/3 - e^2/9 + 5 e^3/81 - 10 e^4/243 + 22 e^5/729 - ...
// cut after e^4 is off by at most 22/729 e^5 < 3e-17 for |e| <= 2^-10, below half an ulp of 1: the result is
// within an ulp of the correctly rounded root, as std::cbrt's is, at a fraction of its cost (the library call
// was 5-6 % of the late stage's wall time). Beyond that range std::cbrt.
#include <cmath>

namespace craterkit::sph {

[[nodiscard]] inline double cube_root_near_one(double x) {
  const double e = x - 1.0;  // exact for x in [0.5, 2] (Sterbenz)
  if (!(std::abs(e) <= 0x1p-10)) return std::cbrt(x);
  return 1.0 + e * (1.0 / 3.0 + e * (-1.0 / 9.0 + e * (5.0 / 81.0 + e * (-10.0 / 243.0))));
}

}  // namespace craterkit::sph
