// cube_root_near_one (cube_root_near_one.hpp): the binomial series near 1 against the cube root taken in
// long double, within an ulp everywhere it is used, and std::cbrt itself beyond that range.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "craterkit/sph/integration/cube_root_near_one.hpp"

using craterkit::sph::cube_root_near_one;

namespace {

// |a - b| in units of the last place of b (b > 0).
double ulps_apart(double a, double b) {
  return std::abs(a - b) / (std::nextafter(b, 2.0 * b) - b);
}

double long_double_root(double x) {
  return static_cast<double>(std::cbrt(static_cast<long double>(x)));
}

}  // namespace

TEST(CubeRootNearOne, WithinAnUlpOfTheRootAcrossTheSeriesRange) {
  std::mt19937_64 random(20261206);
  std::uniform_real_distribution<double> offset(-0x1p-10, 0x1p-10);
  double worst = 0.0;
  for (int k = 0; k < 200000; ++k) {
    const double x = 1.0 + offset(random) * (k % 2 == 0 ? 1.0 : 1e-6);
    worst = std::max(worst, ulps_apart(cube_root_near_one(x), long_double_root(x)));
  }
  EXPECT_LE(worst, 1.0);
  // The ends of the range, where the first term left out is largest.
  for (const double x : {1.0 + 0x1p-10, 1.0 - 0x1p-10}) {
    EXPECT_LE(ulps_apart(cube_root_near_one(x), long_double_root(x)), 1.0) << x;
  }
}

TEST(CubeRootNearOne, OneIsExactAndFarRatiosTakeTheLibraryRoot) {
  EXPECT_EQ(cube_root_near_one(1.0), 1.0);
  for (const double x : {0.5, 0.9, 1.0 + 0x1p-9, 1.5, 8.0, 1e-30}) {
    EXPECT_EQ(cube_root_near_one(x), std::cbrt(x)) << x;
  }
  EXPECT_TRUE(std::isnan(cube_root_near_one(std::numeric_limits<double>::quiet_NaN())));
}
