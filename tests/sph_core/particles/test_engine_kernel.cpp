// Kernels: normalisation (integral of W over space = 1), derivative against finite differences,
// compact support 2h, and the value at the origin against the published normalisation.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "craterkit/sph/particles/kernel.hpp"

using namespace craterkit::sph;

namespace {

template <class K>
double volume_integral(double h) {
  // 4 pi int_0^{2h} W(r) r^2 dr by Simpson's rule on 20000 intervals.
  const int n = 20000;
  const double b = 2.0 * h, dr = b / n;
  double sum = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double r = k * dr;
    const double w = (k == 0 || k == n) ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
    sum += w * K::value(r, h) * r * r;
  }
  return 4.0 * std::numbers::pi * sum * dr / 3.0;
}

template <class K>
void check_derivative(double h) {
  for (double q = 0.05; q < 2.0; q += 0.0731) {
    const double r = q * h, e = 1e-6 * h;
    const double fd = (K::value(r + e, h) - K::value(r - e, h)) / (2.0 * e);
    EXPECT_NEAR(K::derivative(r, h), fd, 1e-6 * std::abs(K::value(0.0, h)) / h) << "q = " << q;
    EXPECT_LE(K::derivative(r, h), 0.0);
  }
}

}  // namespace

TEST(Kernel, CubicSplineIsNormalised) {
  for (double h : {0.1, 1.0, 3.7}) EXPECT_NEAR(volume_integral<CubicSpline>(h), 1.0, 1e-9);
}

TEST(Kernel, WendlandC2IsNormalised) {
  for (double h : {0.1, 1.0, 3.7}) EXPECT_NEAR(volume_integral<WendlandC2>(h), 1.0, 1e-9);
}

TEST(Kernel, CentralValuesMatchPublishedNormalisation) {
  // M4: W(0) = 1/(pi h^3); Wendland C2 with support H = 2h: W(0) = 21/(2 pi H^3).
  EXPECT_DOUBLE_EQ(CubicSpline::value(0.0, 1.0), 1.0 / std::numbers::pi);
  EXPECT_DOUBLE_EQ(WendlandC2::value(0.0, 1.0), 21.0 / (2.0 * std::numbers::pi * 8.0));
}

TEST(Kernel, DerivativesMatchFiniteDifferences) {
  check_derivative<CubicSpline>(0.7);
  check_derivative<WendlandC2>(0.7);
}

TEST(Kernel, CompactSupportIsTwoH) {
  EXPECT_EQ(CubicSpline::value(2.0, 1.0), 0.0);
  EXPECT_EQ(WendlandC2::value(2.0, 1.0), 0.0);
  EXPECT_EQ(CubicSpline::derivative(2.5, 1.0), 0.0);
  EXPECT_GT(CubicSpline::value(1.999, 1.0), 0.0);
  EXPECT_GT(WendlandC2::value(1.999, 1.0), 0.0);
  // M4 is continuous at q = 1: both branches give 1/(4 pi h^3).
  EXPECT_NEAR(CubicSpline::value(1.0 - 1e-12, 1.0), 0.25 / std::numbers::pi, 1e-10);
}
