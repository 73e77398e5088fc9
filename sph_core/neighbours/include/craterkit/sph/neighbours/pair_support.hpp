#pragma once
// Whether a neighbour-list entry of particle i lies within the kernel support, r < h_i + h_j, measured as
// the rate pass measures it (rates/src/pair_geometry.hpp: the neighbour or its mirror image, the minimum
// image on periodic axes). Lists may hold a superset of the pairs within the support (a search skin, lists
// kept across substeps: neighbour_search.hpp); whatever reads them to decide something (the block schedule's
// neighbour rule, the neighbours whose state a substep must refresh) tests each entry with this, so that
// the decision depends on the positions alone and not on when the lists were searched.
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "craterkit/sph/particles/box.hpp"
#include "craterkit/sph/particles/minimum_image.hpp"
#include "craterkit/sph/particles/mirror_image.hpp"
#include "craterkit/sph/particles/particles.hpp"

namespace craterkit::sph {

struct PairSupport {
  const double* x = nullptr;
  const double* y = nullptr;
  const double* z = nullptr;
  const double* h = nullptr;
  std::array<double, 3> period{0.0, 0.0, 0.0};  // 0: open axis
  std::array<double, 3> half{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                             std::numeric_limits<double>::infinity()};
  MirrorPlanes planes{};

  [[nodiscard]] bool operator()(std::size_t i, std::uint32_t entry) const noexcept {
    const MirrorImage image = mirror_image(entry);
    const std::size_t j = image.index;
    const double dx = minimum_image(x[i] - image.position(0, planes, x[j]), period[0], half[0]);
    const double dy = minimum_image(y[i] - image.position(1, planes, y[j]), period[1], half[1]);
    const double dz = minimum_image(z[i] - image.position(2, planes, z[j]), period[2], half[2]);
    const double hsum = h[i] + h[j];
    return dx * dx + dy * dy + dz * dz < hsum * hsum;
  }
};

[[nodiscard]] inline PairSupport pair_support(const Particles& p, const Box& box) {
  PairSupport s{p.x.data(), p.y.data(), p.z.data(), p.smoothing_length.data()};
  for (int a = 0; a < 3; ++a) {
    if (!box.periodic[a]) continue;
    s.period[std::size_t(a)] = box.edge(a);
    s.half[std::size_t(a)] = 0.5 * box.edge(a);
  }
  s.planes = mirror_planes(box);
  return s;
}

}  // namespace craterkit::sph
