// The Sedov-Taylor similarity solution (tests/support) against published constants, its own
// energy integral, and the known analytic limits at the shock and at the centre.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "support/sedov.hpp"

namespace {

using craterkit::test_support::SedovSolution;

TEST(Sedov, Xi0MatchesPublishedValues) {
  // gamma = 5/3: xi0 = 1.15167 (Kamm & Timmes 2007); gamma = 1.4: 1.033
  // (Taylor 1950; Sedov 1959).
  EXPECT_NEAR(SedovSolution(5.0 / 3.0).xi0(), 1.15167, 5e-6);
  EXPECT_NEAR(SedovSolution(1.4).xi0(), 1.033, 5e-4);
}

TEST(Sedov, ShockRadiusScaling) {
  const SedovSolution sedov(5.0 / 3.0);
  // r_s = xi0 (E t^2/rho)^(1/5); E = 1, rho = 1, t = 0.05 -> xi0 * 0.05^0.4.
  EXPECT_DOUBLE_EQ(sedov.shock_radius(1.0, 1.0, 0.05), sedov.xi0() * std::pow(0.05, 0.4));
  EXPECT_NEAR(sedov.shock_radius(1.0, 1.0, 0.05), 0.347468, 1e-6);  // 1.15167 * 0.05^0.4 = 0.34747
}

TEST(Sedov, StrongShockJumpAtTheFront) {
  for (const double g : {1.4, 5.0 / 3.0}) {
    const SedovSolution sedov(g);
    const double rs = sedov.shock_radius(2.0, 3.0, 0.1);
    const double shock_speed = 0.4 * rs / 0.1;
    const auto behind = sedov.state(rs * (1.0 - 1e-12), 2.0, 3.0, 0.1);
    EXPECT_NEAR(behind.density, 3.0 * (g + 1.0) / (g - 1.0), 1e-8);  // 4 rho0 for gamma = 5/3
    EXPECT_NEAR(behind.velocity, 2.0 * shock_speed / (g + 1.0), 1e-8);
    EXPECT_NEAR(behind.pressure, 2.0 * 3.0 * shock_speed * shock_speed / (g + 1.0), 1e-8);
    const auto ahead = sedov.state(rs * 1.001, 2.0, 3.0, 0.1);
    EXPECT_EQ(ahead.density, 3.0);
    EXPECT_EQ(ahead.velocity, 0.0);
    EXPECT_EQ(ahead.pressure, 0.0);
  }
}

TEST(Sedov, ProfilesCarryTheBlastEnergy) {
  // Integrate the sampled profiles (independently of the ODE's energy quadrature) over the sphere.
  const SedovSolution sedov(5.0 / 3.0);
  const double e = 1.0, rho = 1.0, t = 0.05, g = 5.0 / 3.0;
  const double rs = sedov.shock_radius(e, rho, t);
  const int n = 200000;
  double total = 0.0;
  for (int k = 0; k < n; ++k) {  // midpoint rule
    const double r = (k + 0.5) * rs / n;
    const auto s = sedov.state(r, e, rho, t);
    total +=
        (0.5 * s.density * s.velocity * s.velocity + s.pressure / (g - 1.0)) * 4.0 * std::numbers::pi * r * r;
  }
  total *= rs / n;
  EXPECT_NEAR(total, e, 1e-5);
}

TEST(Sedov, CentralAsymptotics) {
  // Near the centre (Sedov 1959): u -> (2/5)(r/t)/gamma (phi/xi -> 1/gamma), the pressure tends to a
  // finite value, and rho ~ xi^(3/(gamma-1)) (xi^4.5 for gamma = 5/3). Checked at xi = 2e-3..1e-2, where
  // the profiles still come from the ODE integration (below 1e-3 they are these power laws by construction).
  for (const double g : {1.4, 5.0 / 3.0}) {
    const SedovSolution sedov(g);
    EXPECT_NEAR(sedov.velocity_ratio(2e-3) / 2e-3, 1.0 / g, 1e-4);
    EXPECT_NEAR(sedov.pressure_ratio(2e-3) / sedov.pressure_ratio(1e-2), 1.0, 1e-5);
    const double slope = std::log(sedov.density_ratio(4e-3) / sedov.density_ratio(2e-3)) / std::log(2.0);
    EXPECT_NEAR(slope, 3.0 / (g - 1.0), 1e-3);
  }
  EXPECT_THROW(SedovSolution(1.0), std::invalid_argument);
}

}  // namespace
