#include "craterkit/sph/rates/artificial_stress.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace craterkit::sph {

std::array<double, 6> artificial_stress_tensor(const std::array<double, 6>& sigma,
                                               double inverse_density_squared, double epsilon) {
  const double xx = sigma[0], xy = sigma[1], xz = sigma[2], yy = sigma[3], yz = sigma[4], zz = sigma[5];
  // Gershgorin: every eigenvalue lies below max_a (sigma_aa + sum_b |sigma_ab|); if that bound is not
  // positive, no principal stress is tensile and R = 0 (the common case in a compressed or lithostatic
  // target).
  const double bound = std::max(
      {xx + std::abs(xy) + std::abs(xz), yy + std::abs(xy) + std::abs(yz), zz + std::abs(xz) + std::abs(yz)});
  if (!(bound > 0.0)) return {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  Eigen::Matrix3d m;
  m << xx, xy, xz, xy, yy, yz, xz, yz, zz;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> principal;
  principal.computeDirect(m);
  const Eigen::Vector3d& values = principal.eigenvalues();
  const Eigen::Matrix3d& axes = principal.eigenvectors();  // columns: principal directions
  Eigen::Vector3d r;
  for (int a = 0; a < 3; ++a) r[a] = values[a] > 0.0 ? -epsilon * values[a] * inverse_density_squared : 0.0;
  const Eigen::Matrix3d R = axes * r.asDiagonal() * axes.transpose();
  return {R(0, 0), R(0, 1), R(0, 2), R(1, 1), R(1, 2), R(2, 2)};
}

}  // namespace craterkit::sph
