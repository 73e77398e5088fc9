#include "craterkit/sph/rates/gradient_correction.hpp"

#include "pair_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace craterkit::sph {

bool invert_symmetric(const std::array<double, 6>& m, std::array<double, 6>& inverse) noexcept {
  const double xx = m[0], xy = m[1], xz = m[2], yy = m[3], yz = m[4], zz = m[5];
  const double c_xx = yy * zz - yz * yz;  // cofactors (symmetric)
  const double c_xy = xz * yz - xy * zz;
  const double c_xz = xy * yz - xz * yy;
  const double det = xx * c_xx + xy * c_xy + xz * c_xz;
  const double n0 = std::sqrt(xx * xx + xy * xy + xz * xz);
  const double n1 = std::sqrt(xy * xy + yy * yy + yz * yz);
  const double n2 = std::sqrt(xz * xz + yz * yz + zz * zz);
  if (!(std::abs(det) > 1e-3 * n0 * n1 * n2)) return false;
  const double r = 1.0 / det;
  inverse = {c_xx * r,
             c_xy * r,
             c_xz * r,
             (xx * zz - xz * xz) * r,
             (xy * xz - xx * yz) * r,
             (xx * yy - xy * xy) * r};
  return true;
}

double smallest_eigenvalue(const std::array<double, 6>& m) noexcept {
  // Cyclic Jacobi rotations (Golub & Van Loan, Matrix Computations, section 8.5): accurate to round-off
  // also for (nearly) repeated eigenvalues, as at the edges and corners of a lattice, where the closed
  // trigonometric form loses half the digits (the eigenvalues of mirror-image particles then differed by
  // 1e-9). Converges quadratically; six sweeps are far more than a 3x3 matrix needs.
  double a[3][3] = {{m[0], m[1], m[2]}, {m[1], m[3], m[4]}, {m[2], m[4], m[5]}};
  for (int sweep = 0; sweep < 6; ++sweep) {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const double diagonal = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (!(off > 1e-34 * diagonal)) break;
    for (int p = 0; p < 2; ++p) {
      for (int q = p + 1; q < 3; ++q) {
        if (a[p][q] == 0.0) continue;
        // Rotation in the (p, q) plane that zeroes a[p][q]: t = tan(angle), the smaller root.
        const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        const double t = (theta >= 0.0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < 3; ++k) {  // columns p and q
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {  // rows p and q
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
      }
    }
  }
  return std::min({a[0][0], a[1][1], a[2][2]});
}

std::array<double, 6> correction_matrix(std::array<double, 6> M) noexcept {
  // Where a direction is short of neighbours (edges, corners, splashes) M is lifted so that its smallest
  // eigenvalue is min_correction_eigenvalue: L is bounded by its inverse. The eigenvalue is needed only when
  // the Gershgorin bound (every eigenvalue lies within sum_b!=a |M_ab| of some M_aa) does not already put
  // it above the floor, with a margin far beyond the Jacobi rotations' round-off (so the result is the same
  // as with the eigenvalue): in the interior of a lattice and on its faces (bound ~1 and ~0.49) the
  // rotations are skipped (bench/RESULTS.md: 1.5 % of the solid bench's instructions).
  const double gershgorin =
      std::min({M[0] - std::abs(M[1]) - std::abs(M[2]), M[3] - std::abs(M[1]) - std::abs(M[4]),
                M[5] - std::abs(M[2]) - std::abs(M[4])});
  if (!(gershgorin > min_correction_eigenvalue * (1.0 + 1e-9))) {
    const double lift = min_correction_eigenvalue - smallest_eigenvalue(M);
    if (lift > 0.0) {
      M[0] += lift;
      M[3] += lift;
      M[5] += lift;
    }
  }
  std::array<double, 6> L{1.0, 0.0, 0.0, 1.0, 0.0, 1.0};
  (void)invert_symmetric(M, L);  // cannot fail once lifted (M = 0, no neighbours, gives 2.5 I)
  return L;
}

namespace {

template <class Kernel, bool mirrored>
void correction_impl(Particles& p, const PairList& pairs, const RateOptions& options, const double* volume,
                     const ParticleSelection& selection) {
  const auto n = static_cast<std::int64_t>(selection.size());
  const detail::PairFrame frame = detail::pair_frame(p, options.period, options.mirror);
  const std::uint8_t* flags = p.flags.data();
  const std::uint64_t* offsets = pairs.offsets.data();
  const std::uint64_t* ends = pairs.ends_of();
  const std::uint32_t* neighbours = pairs.neighbours.data();

  // firstprivate: each thread's own copy of the frame (1 % fewer instructions than through the pointer to
  // the shared one).
#pragma omp parallel for schedule(dynamic, 128) firstprivate(frame)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = selection.at(static_cast<std::size_t>(ii));
    if ((flags[i] & particle_ejected) != 0) continue;
    const detail::PairCentre centre = detail::pair_centre(frame, i);
    // sum_j V_j (x_j - x_i) (x) grad_i W_ij = -sum_j V_j (dW/dr / r) x_ij (x) x_ij, x_ij = x_i - x_j.
    std::array<double, 6> M{0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    for (std::uint64_t k = offsets[i]; k < ends[i]; ++k) {
      const detail::PairGeometry pair = detail::pair_geometry<mirrored>(frame, centre, neighbours[k]);
      if (pair.beyond_support() || pair.coincident()) continue;
      const detail::KernelGradient grad = detail::kernel_gradient<Kernel>(pair);
      const double w = -volume[pair.j()] * grad.dwdr / grad.r;
      const double dx = pair.dx, dy = pair.dy, dz = pair.dz;
      M[0] += w * dx * dx;
      M[1] += w * dx * dy;
      M[2] += w * dx * dz;
      M[3] += w * dy * dy;
      M[4] += w * dy * dz;
      M[5] += w * dz * dz;
    }
    const std::array<double, 6> L = correction_matrix(M);
    p.correction_xx[i] = L[0];
    p.correction_xy[i] = L[1];
    p.correction_xz[i] = L[2];
    p.correction_yy[i] = L[3];
    p.correction_yz[i] = L[4];
    p.correction_zz[i] = L[5];
  }
}

}  // namespace

void compute_correction_matrices(Particles& particles, const PairList& pairs, const RateOptions& options,
                                 const RateWorkspace& workspace, const ParticleSelection& selection) {
  with_kernel(options.kernel, [&](auto kernel) {
    using K = decltype(kernel);
    if (options.mirror.any()) {
      correction_impl<K, true>(particles, pairs, options, workspace.volume.data(), selection);
    } else {
      correction_impl<K, false>(particles, pairs, options, workspace.volume.data(), selection);
    }
  });
}

}  // namespace craterkit::sph
