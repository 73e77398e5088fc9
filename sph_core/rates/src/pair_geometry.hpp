#pragma once
// The prologue every pair loop of the rates layer runs per neighbour-list entry (rates.cpp,
// gradient_correction.cpp, summation_density.cpp): the neighbour or its mirror image (mirror_image.hpp),
// the separation x_i - x_j on the minimum image of periodic axes, r^2, the pair support h_i + h_j and, for
// pairs within it, the kernel gradient at the mean smoothing length (kernel.hpp: W_ij = W(r, hbar), hbar =
// (h_i + h_j)/2). Private to the rates layer.
//
// Every expression is the one the loops spelled out, in the same order, so that the results are bitwise
// those of a loop that writes the prologue itself; the functions are forced inline, so that a j-loop keeps
// its values in registers.
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "craterkit/sph/particles/minimum_image.hpp"
#include "craterkit/sph/particles/mirror_image.hpp"
#include "craterkit/sph/particles/particles.hpp"

namespace craterkit::sph::detail {

// Where a pass measures separations: positions and smoothing lengths of every particle, the periods
// and the mirror planes the neighbour lists were built with. One per pass.
struct PairFrame {
  const double* x;
  const double* y;
  const double* z;
  const double* h;
  double Lx, Ly, Lz;  // period along each axis, 0 = not periodic
  double hx, hy, hz;  // half the period; +infinity on open axes, where minimum_image never wraps
  MirrorPlanes planes;
};

[[nodiscard]] inline PairFrame pair_frame(const Particles& p, const std::array<double, 3>& period,
                                          const MirrorPlanes& planes) noexcept {
  const double inf = std::numeric_limits<double>::infinity();
  const double Lx = period[0], Ly = period[1], Lz = period[2];
  return {p.x.data(),
          p.y.data(),
          p.z.data(),
          p.smoothing_length.data(),
          Lx,
          Ly,
          Lz,
          Lx > 0.0 ? 0.5 * Lx : inf,
          Ly > 0.0 ? 0.5 * Ly : inf,
          Lz > 0.0 ? 0.5 * Lz : inf,
          planes};
}

// Particle i as the prologue reads it.
struct PairCentre {
  double x, y, z, h;
};

[[nodiscard, gnu::always_inline]] inline PairCentre pair_centre(const PairFrame& frame,
                                                                std::size_t i) noexcept {
  return {frame.x[i], frame.y[i], frame.z[i], frame.h[i]};
}

// One list entry of particle i.
struct PairGeometry {
  MirrorImage image;  // the neighbour j (image.index) and the planes its image is reflected across
  double dx, dy, dz;  // x_i - x_j, j's image, on the minimum image of periodic axes
  double r2;          // |x_i - x_j|^2
  double hsum;        // h_i + h_j: the pair support, r < h_i + h_j

  [[nodiscard]] std::size_t j() const noexcept { return image.index; }
  [[nodiscard]] double hbar() const noexcept { return 0.5 * hsum; }
  // r >= h_i + h_j: no interaction (the lists may carry a skin). False for a NaN separation, which then
  // reaches the sums instead of vanishing from them.
  [[nodiscard]] bool beyond_support() const noexcept { return r2 >= hsum * hsum; }
  // r = 0 (a particle on a mirror plane and its own image, or two particles in one place): the kernel
  // gradient has no direction there and is left out.
  [[nodiscard]] bool coincident() const noexcept { return r2 <= 0.0; }
};

template <bool mirrored>
[[nodiscard, gnu::always_inline]] inline PairGeometry pair_geometry(const PairFrame& frame,
                                                                    const PairCentre& i,
                                                                    std::uint32_t entry) noexcept {
  const MirrorImage image = mirror_image<mirrored>(entry);
  const std::size_t j = image.index;
  const double dx = minimum_image(i.x - image.position(0, frame.planes, frame.x[j]), frame.Lx, frame.hx);
  const double dy = minimum_image(i.y - image.position(1, frame.planes, frame.y[j]), frame.Ly, frame.hy);
  const double dz = minimum_image(i.z - image.position(2, frame.planes, frame.z[j]), frame.Lz, frame.hz);
  const double r2 = dx * dx + dy * dy + dz * dz;
  return {image, dx, dy, dz, r2, i.h + frame.h[j]};
}

// The kernel gradient of a pair with 0 < r < h_i + h_j: grad_i W_ij = (dW/dr)(r, hbar) x_ij / r.
struct KernelGradient {
  double r;
  double hbar;
  double dwdr;     // dW/dr at (r, hbar), <= 0
  double x, y, z;  // grad_i W_ij
};

template <class Kernel>
[[nodiscard, gnu::always_inline]] inline KernelGradient kernel_gradient(const PairGeometry& pair) noexcept {
  const double r = std::sqrt(pair.r2);
  const double hbar = pair.hbar();
  const double dwdr = Kernel::derivative(r, hbar);
  const double dwdr_over_r = dwdr / r;
  return {r, hbar, dwdr, pair.dx * dwdr_over_r, pair.dy * dwdr_over_r, pair.dz * dwdr_over_r};
}

}  // namespace craterkit::sph::detail
