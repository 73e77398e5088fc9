// Kernel-gradient correction matrices (gradient_correction.hpp): the symmetric inverse and the smallest
// eigenvalue against Eigen, the Gershgorin shortcut against always lifting, and L on a lattice block: the
// exact inverse of M in the bulk, lifted (largest eigenvalue of L exactly 1/min_correction_eigenvalue) where
// M's smallest eigenvalue is below it: at edges (0.29) and corners (0.23), not on the faces (0.49).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "craterkit/sph/rates/gradient_correction.hpp"
#include "craterkit/sph/neighbours/neighbour_search.hpp"

using namespace craterkit::sph;

namespace {

Eigen::Matrix3d full(const std::array<double, 6>& m) {
  Eigen::Matrix3d out;
  out << m[0], m[1], m[2], m[1], m[3], m[4], m[2], m[4], m[5];
  return out;
}

}  // namespace

TEST(GradientCorrection, InverseAndSmallestEigenvalueAgreeWithEigen) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int inverted = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    // Random symmetric matrices, some with repeated eigenvalues (multiples of the identity plus a rank-one
    // term), some indefinite.
    std::array<double, 6> m{};
    for (auto& v : m) v = u(rng);
    if (trial % 4 == 0) m = {1.0 + 0.5 * u(rng), 0.0, 0.0, 1.0 + 0.5 * u(rng), 0.0, 1.0};
    if (trial % 4 == 1) {
      const double a = u(rng), b = u(rng), c = u(rng), s = 0.7;
      m = {s + a * a, a * b, a * c, s + b * b, b * c, s + c * c};
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(full(m));
    const double scale = full(m).norm();
    EXPECT_NEAR(smallest_eigenvalue(m), solver.eigenvalues()(0), 1e-12 * scale) << "trial " << trial;
    std::array<double, 6> inverse{};
    if (invert_symmetric(m, inverse)) {
      ++inverted;
      const Eigen::Matrix3d product = full(m) * full(inverse);
      EXPECT_LT((product - Eigen::Matrix3d::Identity()).norm(), 1e-9) << "trial " << trial;
    }
  }
  EXPECT_GT(inverted, 1800);
  std::array<double, 6> singular{1.0, 1.0, 0.0, 1.0, 0.0, 0.0};  // rank one in the xy block, zero zz
  std::array<double, 6> untouched{7.0, 7.0, 7.0, 7.0, 7.0, 7.0};
  EXPECT_FALSE(invert_symmetric(singular, untouched));
  EXPECT_EQ(untouched[0], 7.0);
}

// correction_matrix skips the eigenvalue where the Gershgorin bound already puts M above the floor: the
// result must be bitwise that of always lifting by the eigenvalue, also for matrices whose bound or
// smallest eigenvalue lies just above or below min_correction_eigenvalue.
TEST(GradientCorrection, GershgorinShortcutGivesTheSameMatrixAsTheEigenvalue) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int skipped = 0, lifted = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double spread = (trial % 3 == 0) ? 0.02 : (trial % 3 == 1 ? 0.2 : 0.6);
    const double floor = min_correction_eigenvalue;
    std::array<double, 6> M{floor + 0.8 * (1.0 + u(rng)), spread * u(rng), spread * u(rng),
                            floor + 0.8 * (1.0 + u(rng)), spread * u(rng), floor + 0.8 * (1.0 + u(rng))};
    if (trial % 5 == 0) {  // a diagonal entry on the floor plus its row's off-diagonal sum, +- 1e-12
      M[0] = floor + std::abs(M[1]) + std::abs(M[2]) + 1e-12 * u(rng);
    }
    std::array<double, 6> reference = M;
    const double lift = floor - smallest_eigenvalue(M);
    if (lift > 0.0) {
      reference[0] += lift;
      reference[3] += lift;
      reference[5] += lift;
      ++lifted;
    }
    std::array<double, 6> expected{1.0, 0.0, 0.0, 1.0, 0.0, 1.0};
    (void)invert_symmetric(reference, expected);
    const double bound =
        std::min({M[0] - std::abs(M[1]) - std::abs(M[2]), M[3] - std::abs(M[1]) - std::abs(M[4]),
                  M[5] - std::abs(M[2]) - std::abs(M[4])});
    skipped += bound > floor ? 1 : 0;
    EXPECT_EQ(correction_matrix(M), expected) << "trial " << trial;
  }
  EXPECT_GT(skipped, 5000);  // both paths are exercised
  EXPECT_GT(lifted, 1000);
}

// A 10^3 block of unit spacing, h = 1.2: M and L per particle, recomputed here from the lists.
TEST(GradientCorrection, LatticeBlockIsCorrectedInFullAtFacesAndLiftedAtEdgesAndCorners) {
  const int n = 10;
  Particles p;
  p.resize(static_cast<std::size_t>(n * n * n));
  std::size_t k = 0;
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      for (int c = 0; c < n; ++c, ++k) {
        p.id[k] = k;
        p.x[k] = a;
        p.y[k] = b;
        p.z[k] = c;
        p.mass[k] = 1.0;
        p.density[k] = 1.0;
        p.smoothing_length[k] = 1.2;
      }
    }
  }
  NeighbourLists lists;
  NeighbourSearch search;
  search.build(neighbour_input(p), Box{}, lists);
  RateWorkspace workspace;
  workspace.volume.assign(p.size(), 1.0);
  compute_correction_matrices(p, PairList{lists.offsets, lists.neighbours}, RateOptions{}, workspace,
                              ParticleSelection::all(p.size()));
  int faces = 0, lifted = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::array<double, 6> M{};
    for (const auto entry : lists.of(i)) {
      const std::size_t j = neighbour_index(entry);
      const double d[3] = {p.x[i] - p.x[j], p.y[i] - p.y[j], p.z[i] - p.z[j]};
      const double r = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      if (r <= 0.0 || r >= 2.4) continue;
      const double w = -CubicSpline::derivative(r, 1.2) / r;
      M[0] += w * d[0] * d[0];
      M[1] += w * d[0] * d[1];
      M[2] += w * d[0] * d[2];
      M[3] += w * d[1] * d[1];
      M[4] += w * d[1] * d[2];
      M[5] += w * d[2] * d[2];
    }
    const Eigen::Matrix3d L = full({p.correction_xx[i], p.correction_xy[i], p.correction_xz[i],
                                    p.correction_yy[i], p.correction_yz[i], p.correction_zz[i]});
    const double lambda = smallest_eigenvalue(M);
    if (lambda >= min_correction_eigenvalue) {
      // The bulk and the faces: L = M^-1.
      EXPECT_LT((full(M) * L - Eigen::Matrix3d::Identity()).norm(), 1e-12) << "particle " << i;
    } else {
      ++lifted;
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(L);
      EXPECT_NEAR(solver.eigenvalues()(2), 1.0 / min_correction_eigenvalue, 1e-12) << "particle " << i;
    }
    const int on_faces = (p.x[i] == 0 || p.x[i] == n - 1) + (p.y[i] == 0 || p.y[i] == n - 1) +
                         (p.z[i] == 0 || p.z[i] == n - 1);
    if (on_faces == 1) {
      ++faces;
      EXPECT_GT(lambda, min_correction_eigenvalue) << "a flat face is corrected in full";
    }
    if (on_faces >= 2) {
      EXPECT_LT(lambda, min_correction_eigenvalue) << "edges and corners are lifted";
    }
  }
  EXPECT_EQ(faces, 6 * (n - 2) * (n - 2));
  EXPECT_EQ(lifted, 12 * (n - 2) + 8);  // exactly the edges and corners
}
