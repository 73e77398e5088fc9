#pragma once
// The first step of a pair pass in lanes (rates.cpp, summation_density.cpp): the entries of particle i's
// list within the pair support, in list order, with their separations. Private to the rates layer.
//
// Keeping them first makes a pass's sums independent of which superset of the pairs the lists hold (a skin,
// a rebuilt list after a restart): the lanes then take the kept pairs four at a time, so pair k of i always
// lands in lane k mod 4. The separations are taken four entries at a time (the prologue of pair_geometry.hpp
// per lane: the image's position, the minimum image, r^2, h_i + h_j) and kept without a branch (about one
// entry in three is beyond the support in lists with a skin, an unpredictable test).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "craterkit/sph/particles/mirror_image.hpp"
#include "pair_geometry.hpp"
#include "pair_lanes.hpp"

namespace craterkit::sph::detail {

// The kept pairs of one particle i, one per thread, grown to the longest list.
struct PairScratch {
  std::vector<std::uint32_t> entry;
  std::vector<double> dx, dy, dz, r2, hsum;
  void hold(std::size_t n) {
    if (entry.size() >= n) return;
    n += n / 4 + lane_count;
    entry.resize(n);
    for (auto* v : {&dx, &dy, &dz, &r2, &hsum}) v->resize(n);
  }
};

// Lane `lane` of the masks of reflection across the mirror planes of axes x, y, z: all ones where the
// neighbour is an image reflected across that plane, zero where not.
[[gnu::always_inline]] inline void set_reflections(int lane, const MirrorImage& image, LaneMask& x,
                                                   LaneMask& y, LaneMask& z) {
  x[lane] = image.reflected(0) ? -1 : 0;
  y[lane] = image.reflected(1) ? -1 : 0;
  z[lane] = image.reflected(2) ? -1 : 0;
}

// What the pass takes of a pair. The kernel gradient (the rate pass): a pair at r = 0 has no direction and is
// left out, and the separation x_i - x_j is kept. The kernel value (the density sum): r = 0 counts, W has a
// value there, and r^2 and h_i + h_j are all the pass reads (three stores fewer per entry: 8 % of the density
// pass, bench/RESULTS.md).
enum class PairUse { kernel_gradient, kernel_value };

// Keeps the entries first..last of `neighbours` (particle i's list) within the support r < h_i + h_j in
// scratch.entry, .r2, .hsum and (kernel gradients) .dx, .dy, .dz (x_i - x_j on the minimum image); returns
// how many. NaN separations stay (they reach the sums, as a failure that shows).
template <bool mirrored, PairUse use>
[[gnu::always_inline]] inline std::size_t keep_pairs_within_support(const PairFrame& frame,
                                                                    const PairCentre& centre,
                                                                    const std::uint32_t* neighbours,
                                                                    std::uint64_t first, std::uint64_t last,
                                                                    PairScratch& scratch) {
  constexpr int lanes = lane_count;
  scratch.hold(last - first + lanes);  // the last group writes one past the kept entries
  std::size_t kept = 0;
  for (std::uint64_t k = first; k < last; k += lanes) {
    Lanes xj, yj, zj, hj;
    LaneMask valid, flip_x = {0, 0, 0, 0}, flip_y = flip_x, flip_z = flip_x;
    for (int l = 0; l < lanes; ++l) {
      const bool holds = k + l < last;
      const MirrorImage image = mirror_image<mirrored>(neighbours[holds ? k + l : k]);
      const std::size_t j = image.index;
      valid[l] = holds ? -1 : 0;
      xj[l] = frame.x[j];
      yj[l] = frame.y[j];
      zj[l] = frame.z[j];
      hj[l] = frame.h[j];
      if constexpr (mirrored) set_reflections(l, image, flip_x, flip_y, flip_z);
    }
    if constexpr (mirrored) {  // 2 L_a - x_a across the plane of axis a (mirror_image.hpp)
      xj = flip_x ? 2.0 * frame.planes.position[0] - xj : xj;
      yj = flip_y ? 2.0 * frame.planes.position[1] - yj : yj;
      zj = flip_z ? 2.0 * frame.planes.position[2] - zj : zj;
    }
    Lanes dx = centre.x - xj, dy = centre.y - yj, dz = centre.z - zj;
    // minimum_image.hpp; the half periods are infinite on open axes, where nothing wraps.
    dx = dx > frame.hx ? dx - frame.Lx : (dx < -frame.hx ? dx + frame.Lx : dx);
    dy = dy > frame.hy ? dy - frame.Ly : (dy < -frame.hy ? dy + frame.Ly : dy);
    dz = dz > frame.hz ? dz - frame.Lz : (dz < -frame.hz ? dz + frame.Lz : dz);
    const Lanes r2 = dx * dx + dy * dy + dz * dz;
    const Lanes hsum = centre.h + hj;
    LaneMask within = ~(r2 >= hsum * hsum) & valid;
    if constexpr (use == PairUse::kernel_gradient) within &= ~(r2 <= 0.0);
    for (int l = 0; l < lanes; ++l) {
      scratch.entry[kept] = neighbours[k + l < last ? k + l : k];
      if constexpr (use == PairUse::kernel_gradient) {
        scratch.dx[kept] = dx[l];
        scratch.dy[kept] = dy[l];
        scratch.dz[kept] = dz[l];
      }
      scratch.r2[kept] = r2[l];
      scratch.hsum[kept] = hsum[l];
      kept += within[l] != 0 ? 1 : 0;
    }
  }
  return kept;
}

}  // namespace craterkit::sph::detail
