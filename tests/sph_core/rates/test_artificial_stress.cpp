// Artificial stress (artificial_stress.hpp; Monaghan 2000, Gray, Monaghan & Swift 2001): the per-particle
// tensor R against hand-computed principal stresses, its covariance under rotation, and zero in compression.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <array>
#include <cmath>

#include "craterkit/sph/rates/artificial_stress.hpp"

using namespace craterkit::sph;

namespace {

std::array<double, 6> packed(const Eigen::Matrix3d& m) {
  return {m(0, 0), m(0, 1), m(0, 2), m(1, 1), m(1, 2), m(2, 2)};
}

Eigen::Matrix3d unpacked(const std::array<double, 6>& s) {
  Eigen::Matrix3d m;
  m << s[0], s[1], s[2], s[1], s[3], s[4], s[2], s[4], s[5];
  return m;
}

}  // namespace

// Principal axes along x, y, z: R'_aa = -epsilon sigma_aa / rho^2 for the tensile ones only.
TEST(ArtificialStress, DiagonalStressGivesMinusEpsilonTimesTheTensileComponents) {
  const double inverse_density_squared = 1.0 / (2000.0 * 2000.0);
  const auto R = artificial_stress_tensor({2e6, 0.0, 0.0, -1e6, 0.0, 5e5}, inverse_density_squared, 0.3);
  EXPECT_NEAR(R[0], -0.3 * 2e6 * inverse_density_squared, 1e-15);
  EXPECT_NEAR(R[3], 0.0, 1e-15);
  EXPECT_NEAR(R[5], -0.3 * 5e5 * inverse_density_squared, 1e-15);
  EXPECT_NEAR(R[1], 0.0, 1e-15);
  EXPECT_NEAR(R[2], 0.0, 1e-15);
  EXPECT_NEAR(R[4], 0.0, 1e-15);
}

// No tensile principal stress, no artificial stress: once caught by the Gershgorin bound (all rows
// negative), once where the bound is positive (row x: -1 + 1.5 > 0) but both eigenvalues of the xy block,
// -2 +- sqrt(3.25), are negative.
TEST(ArtificialStress, ZeroWithoutTension) {
  for (const auto& sigma : {std::array<double, 6>{-1.0, 0.2, 0.1, -2.0, 0.3, -3.0},
                            std::array<double, 6>{-1.0, 1.5, 0.0, -3.0, 0.0, -0.5}}) {
    const auto R = artificial_stress_tensor(sigma, 1.0, 0.3);
    for (double r : R) EXPECT_NEAR(r, 0.0, 1e-15);
  }
}

// R is built in the principal frame and rotated back, so R(Q sigma Q^T) = Q R(sigma) Q^T for any
// rotation Q, with mixed signs of the principal stresses.
TEST(ArtificialStress, CovariantUnderRotation) {
  const Eigen::Matrix3d Q = (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, 2.0, -0.5).normalized()) *
                             Eigen::AngleAxisd(-1.1, Eigen::Vector3d::UnitZ()))
                                .toRotationMatrix();
  const Eigen::Matrix3d principal = Eigen::Vector3d(3.0, -1.0, 0.5).asDiagonal();
  const Eigen::Matrix3d sigma = Q * principal * Q.transpose();
  const Eigen::Matrix3d expected =
      Q * Eigen::Vector3d(-0.3 * 3.0 * 0.25, 0.0, -0.3 * 0.5 * 0.25).asDiagonal() * Q.transpose();
  const Eigen::Matrix3d R = unpacked(artificial_stress_tensor(packed(sigma), 0.25, 0.3));
  EXPECT_LT((R - expected).norm(), 1e-13);
}
