#include "craterkit/sph/rates/summation_density.hpp"

#include "pair_geometry.hpp"

#include <cmath>
#include <cstdint>

namespace craterkit::sph {

namespace {

template <class Kernel, bool mirrored>
void summation_impl(Particles& p, const PairList& pairs, const std::array<double, 3>& period,
                    const MirrorPlanes& planes) {
  const auto n = static_cast<std::int64_t>(p.size());
  const detail::PairFrame frame = detail::pair_frame(p, period, planes);
  const double* mass = p.mass.data();
  const std::uint8_t* flags = p.flags.data();
  double* density = p.density.data();
  const std::uint64_t* offsets = pairs.offsets.data();
  const std::uint64_t* ends = pairs.ends_of();
  const std::uint32_t* neighbours = pairs.neighbours.data();

#pragma omp parallel for schedule(dynamic, 128)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if ((flags[i] & (particle_fixed | particle_ejected)) != 0) continue;
    const detail::PairCentre centre = detail::pair_centre(frame, i);
    double sum = mass[i] * Kernel::value(0.0, centre.h);
    for (std::uint64_t k = offsets[i]; k < ends[i]; ++k) {
      const detail::PairGeometry pair = detail::pair_geometry<mirrored>(frame, centre, neighbours[k]);
      if (pair.beyond_support()) continue;  // (r = 0 counts: W has a value there)
      sum += mass[pair.j()] * Kernel::value(std::sqrt(pair.r2), pair.hbar());
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
