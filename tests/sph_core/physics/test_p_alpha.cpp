// P-alpha porosity kernels: the crush curve of docs/physics.md section 2 (continuity, limits, slope) and a
// quasi-static uniaxial compression driven independently of the solver, which must follow the crush
// curve (the consistent dalpha/dt of Jutzi et al. 2008) and never re-expand on unloading.
#include <gtest/gtest.h>

#include <cmath>

#include "craterkit/sph/physics/p_alpha.hpp"

namespace {
using namespace craterkit::sph;

const PAlphaParameters kNominal{};  // alpha0 = 2, alpha_t = 1.25, P_e = 1 MPa, P_t = 68 MPa, P_s = 213 MPa

TEST(PAlpha, CrushCurveLimitsAndContinuity) {
  EXPECT_DOUBLE_EQ(crush_curve_distention(kNominal, 0.0), 2.0);
  EXPECT_DOUBLE_EQ(crush_curve_distention(kNominal, 1.0e6), 2.0);
  EXPECT_NEAR(crush_curve_distention(kNominal, 1.0e6 * (1 + 1e-12)), 2.0, 1e-9);
  EXPECT_DOUBLE_EQ(crush_curve_distention(kNominal, 213.0e6), 1.0);
  EXPECT_NEAR(crush_curve_distention(kNominal, 213.0e6 * (1 - 1e-12)), 1.0, 1e-9);
  // At P_t only the second term remains: (alpha_t - 1) ((P_s - P_t)/(P_s - P_e))^3 + 1.
  const double at_t = 0.25 * std::pow(145.0 / 212.0, 3.0) + 1.0;
  EXPECT_NEAR(crush_curve_distention(kNominal, 68.0e6), at_t, 1e-14);
  EXPECT_NEAR(crush_curve_distention(kNominal, 68.0e6 * (1 - 1e-12)), at_t, 1e-9);
  // A hand value inside the first segment, P = 10 MPa.
  const double hand = 0.75 * std::pow(58.0 / 67.0, 12.0) + 0.25 * std::pow(203.0 / 212.0, 3.0) + 1.0;
  EXPECT_NEAR(crush_curve_distention(kNominal, 10.0e6), hand, 1e-14);
}

TEST(PAlpha, SlopeMatchesFiniteDifference) {
  for (double p : {2.0e6, 10.0e6, 50.0e6, 67.0e6, 69.0e6, 150.0e6, 212.0e6}) {
    const double dp = p * 1e-6;
    const double fd =
        (crush_curve_distention(kNominal, p + dp) - crush_curve_distention(kNominal, p - dp)) / (2 * dp);
    EXPECT_NEAR(crush_curve_slope(kNominal, p), fd, 1e-6 * std::abs(fd) + 1e-18) << p;
    EXPECT_LT(crush_curve_slope(kNominal, p), 0.0);
  }
  EXPECT_EQ(crush_curve_slope(kNominal, 0.5e6), 0.0);
  EXPECT_EQ(crush_curve_slope(kNominal, 300.0e6), 0.0);
}

// Energy-free linear matrix law P_m = K (rho_m / rho_s - 1), the driver's independent matrix model.
struct LinearMatrix {
  double bulk_modulus = 26.7e9;
  double solid_density = 2600.0;
  [[nodiscard]] double pressure(double matrix_density) const {
    return bulk_modulus * (matrix_density / solid_density - 1.0);
  }
};

TEST(PAlpha, QuasiStaticCompressionFollowsCrushCurveAndNeverReExpands) {
  const LinearMatrix matrix;
  double alpha = kNominal.initial_distention;
  double rho = matrix.solid_density / alpha;  // stress-free start, P = 0
  const double strain_rate = 1.0;             // drho/dt / rho, 1/s (quasi-static: no inertia in this driver)
  const double dt = 2e-6;
  double worst_relative = 0.0;
  double last_alpha = alpha;
  bool reached_solid = false;
  // Load until fully compacted, following P = P_m(alpha rho)/alpha and the consistent dalpha/dt.
  for (int n = 0; n < 2000000 && !reached_solid; ++n) {
    const double p = matrix.pressure(alpha * rho) / alpha;
    const double drho = strain_rate * rho;
    const MatrixResponse response{matrix.bulk_modulus / matrix.solid_density, 0.0};
    const double dalpha = distention_rate(kNominal, alpha, p, rho, drho, 0.0, response);
    EXPECT_LE(dalpha, 0.0);
    alpha = std::max(1.0, alpha + dt * dalpha);
    rho += dt * drho;
    const double p_new = matrix.pressure(alpha * rho) / alpha;
    if (p_new > 1.05 * kNominal.elastic_pressure && p_new < kNominal.solid_pressure) {
      const double curve = crush_curve_distention(kNominal, p_new);
      worst_relative = std::max(worst_relative, std::abs(alpha - curve) / curve);
    }
    EXPECT_LE(alpha, last_alpha + 1e-15);
    last_alpha = alpha;
    reached_solid = p_new >= kNominal.solid_pressure;
  }
  EXPECT_TRUE(reached_solid);
  EXPECT_LT(worst_relative, 0.02);  // within 2 % of the crush curve
  // Unload: alpha must stay where it is.
  const double alpha_loaded = alpha;
  for (int n = 0; n < 100000; ++n) {
    const double p = matrix.pressure(alpha * rho) / alpha;
    const double drho = -strain_rate * rho;
    const double dalpha = distention_rate(kNominal, alpha, p, rho, drho, 0.0,
                                          {matrix.bulk_modulus / matrix.solid_density, 0.0});
    EXPECT_EQ(dalpha, 0.0);
    rho += dt * drho;
  }
  EXPECT_EQ(alpha, alpha_loaded);
}

TEST(PAlpha, PartialLoadThenReloadResumesOnTheCurve) {
  // Load to 30 MPa, unload to 5 MPa (alpha frozen), reload: no compaction until the curve is met again.
  const LinearMatrix matrix;
  const MatrixResponse response{matrix.bulk_modulus / matrix.solid_density, 0.0};
  double alpha = kNominal.initial_distention, rho = matrix.solid_density / alpha;
  const double dt = 2e-6;
  auto step = [&](double sign) {
    const double p = matrix.pressure(alpha * rho) / alpha;
    const double drho = sign * rho;
    alpha = std::max(1.0, alpha + dt * distention_rate(kNominal, alpha, p, rho, drho, 0.0, response));
    rho += dt * drho;
    return matrix.pressure(alpha * rho) / alpha;
  };
  while (step(+1.0) < 30.0e6) {
  }
  const double alpha_peak = alpha;
  while (step(-1.0) > 5.0e6) {
  }
  EXPECT_EQ(alpha, alpha_peak);
  double p = 0.0;
  while ((p = step(+1.0)) < 29.0e6) EXPECT_EQ(alpha, alpha_peak) << p;
  while ((p = step(+1.0)) < 40.0e6) {
  }
  EXPECT_LT(alpha, alpha_peak);
  EXPECT_NEAR(alpha, crush_curve_distention(kNominal, p), 0.02 * alpha);
}

}  // namespace
