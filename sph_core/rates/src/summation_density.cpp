#include "craterkit/sph/rates/summation_density.hpp"

#include "craterkit/sph/particles/minimum_image.hpp"

#include <cmath>
#include <cstdint>
#include <limits>

namespace craterkit::sph {

namespace {

template <class Kernel, bool mirrored>
void summation_impl(Particles& p, const PairList& pairs, const std::array<double, 3>& period,
                    const MirrorPlanes& planes) {
  const auto n = static_cast<std::int64_t>(p.size());
  const double* x = p.x.data();
  const double* y = p.y.data();
  const double* z = p.z.data();
  const double* h = p.smoothing_length.data();
  const double* mass = p.mass.data();
  const std::uint8_t* flags = p.flags.data();
  double* density = p.density.data();
  const std::uint64_t* offsets = pairs.offsets.data();
  const std::uint32_t* neighbours = pairs.neighbours.data();
  const double inf = std::numeric_limits<double>::infinity();
  const double Lx = period[0], Ly = period[1], Lz = period[2];
  const double hx = Lx > 0.0 ? 0.5 * Lx : inf, hy = Ly > 0.0 ? 0.5 * Ly : inf, hz = Lz > 0.0 ? 0.5 * Lz : inf;

#pragma omp parallel for schedule(dynamic, 128)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if ((flags[i] & (particle_fixed | particle_ejected)) != 0) continue;
    const double xi = x[i], yi = y[i], zi = z[i], hi = h[i];
    double sum = mass[i] * Kernel::value(0.0, hi);
    for (std::uint64_t k = offsets[i]; k < offsets[i + 1]; ++k) {
      const MirrorImage image = mirror_image<mirrored>(neighbours[k]);  // the neighbour, or its mirror image
      const std::size_t j = image.index;
      const double dx = minimum_image(xi - image.position(0, planes, x[j]), Lx, hx);
      const double dy = minimum_image(yi - image.position(1, planes, y[j]), Ly, hy);
      const double dz = minimum_image(zi - image.position(2, planes, z[j]), Lz, hz);
      const double hsum = hi + h[j];
      const double r2 = dx * dx + dy * dy + dz * dz;
      if (r2 >= hsum * hsum) continue;  // beyond the pair support (lists may carry a skin)
      sum += mass[j] * Kernel::value(std::sqrt(r2), 0.5 * hsum);
    }
    density[i] = sum;
  }
}

}  // namespace

void compute_summation_density(Particles& particles, const PairList& pairs, KernelType kernel,
                               const std::array<double, 3>& period, const MirrorPlanes& mirror) {
  with_kernel(kernel, [&](auto k) {
    if (mirror.any()) {
      summation_impl<decltype(k), true>(particles, pairs, period, mirror);
    } else {
      summation_impl<decltype(k), false>(particles, pairs, period, mirror);
    }
  });
}

std::string_view density_method_name(DensityMethod method) noexcept {
  return method == DensityMethod::summation ? "summation" : "continuity";
}

}  // namespace craterkit::sph
