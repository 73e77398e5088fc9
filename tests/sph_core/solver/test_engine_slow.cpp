// Slow Sedov validation (label slow): 50^3 particles (binned peak density >= 2.4, radius within 3 %,
// energy to 5e-4) and 100^3 = 1e6 particles (radius within 2 %).
#include <gtest/gtest.h>

#include <cstdio>

#include "sph_core/engine_sedov_common.hpp"

namespace {
void report(const char* name, const engine_test::SedovMeasurement& m) {
  std::printf("%s: r_s %.5f (analytic %.5f, %+.2f %%), peak %.3f, L1 %.4f, dE %.2e, %llu steps\n", name,
              m.shock_radius, m.analytic_radius, 100.0 * (m.shock_radius / m.analytic_radius - 1.0),
              m.peak_density, m.profile_l1, m.energy_error, static_cast<unsigned long long>(m.steps));
}
}  // namespace

TEST(SedovBlastSlow, Resolution50Cubed) {
  const auto m = engine_test::run_sedov(50);
  report("Sedov 50^3", m);
  EXPECT_GE(m.peak_density, 2.4);
  EXPECT_NEAR(m.shock_radius / m.analytic_radius, 1.0, 0.03);
  EXPECT_LT(m.energy_error, 5e-4);
}

TEST(SedovBlastSlow, Resolution100Cubed) {
  const auto m = engine_test::run_sedov(100);
  report("Sedov 100^3", m);
  EXPECT_NEAR(m.shock_radius / m.analytic_radius, 1.0, 0.02);
  EXPECT_LT(m.energy_error, 5e-4);
}
