#include "craterkit/sph/rates/summation_density.hpp"

#include "pair_geometry.hpp"
#include "pair_keeping.hpp"
#include "pair_lanes.hpp"

#include <cmath>
#include <cstdint>

namespace craterkit::sph {

namespace {

using detail::LaneMask;
using detail::Lanes;
using detail::PairCentre;
using detail::PairFrame;

// The sum of particle i over its neighbours: the pairs within the support kept first (pair_keeping.hpp; r = 0
// counts, W has a value there), then m_j W(r_ij, hbar_ij) of four pairs at a time (pair_lanes.hpp), each
// lane's term the scalar expression's bit for bit; a lane that holds no pair (the last group's padding) is
// left out by a select.
template <class Kernel, bool mirrored>
[[gnu::always_inline]] inline double pair_sum(const PairFrame& frame, const double* mass,
                                              const std::uint32_t* neighbours, std::uint64_t first,
                                              std::uint64_t last, const PairCentre& centre,
                                              detail::PairScratch& scratch) {
  constexpr int lanes = detail::lane_count;
  const std::size_t kept = detail::keep_pairs_within_support<mirrored, detail::PairUse::kernel_value>(
      frame, centre, neighbours, first, last, scratch);
  const Lanes zero = {0.0, 0.0, 0.0, 0.0};
  Lanes sum = zero;
  for (std::size_t k = 0; k < kept; k += lanes) {
    Lanes r2, hsum, mj;
    LaneMask valid;
    for (int l = 0; l < lanes; ++l) {
      const bool holds = k + l < kept;
      const std::size_t at = holds ? k + l : k;
      valid[l] = holds ? -1 : 0;
      r2[l] = scratch.r2[at];
      hsum[l] = scratch.hsum[at];
      mj[l] = mass[neighbour_index(scratch.entry[at])];
    }
    Lanes r, w;
    detail::lane_sqrt(r2, r);
    detail::kernel_value<Kernel>(r, 0.5 * hsum, w);
    sum += valid ? mj * w : zero;
  }
  return detail::lane_sum(sum);
}

// pair_sum compiled for the baseline processor and for AVX2 (pair_lanes.hpp).
template <class Kernel, bool mirrored>
[[gnu::noinline]] double pair_sum_baseline(const PairFrame& frame, const double* mass,
                                           const std::uint32_t* neighbours, std::uint64_t first,
                                           std::uint64_t last, const PairCentre& centre,
                                           detail::PairScratch& scratch) {
  return pair_sum<Kernel, mirrored>(frame, mass, neighbours, first, last, centre, scratch);
}

template <class Kernel, bool mirrored>
[[gnu::noinline, CRATERKIT_WIDE_LANES]] double pair_sum_wide(const PairFrame& frame, const double* mass,
                                                             const std::uint32_t* neighbours,
                                                             std::uint64_t first, std::uint64_t last,
                                                             const PairCentre& centre,
                                                             detail::PairScratch& scratch) {
  return pair_sum<Kernel, mirrored>(frame, mass, neighbours, first, last, centre, scratch);
}

template <class Kernel, bool mirrored>
void summation_impl(Particles& p, const PairList& pairs, const std::array<double, 3>& period,
                    const MirrorPlanes& planes, bool wide_lanes) {
  const auto n = static_cast<std::int64_t>(p.size());
  const PairFrame frame = detail::pair_frame(p, period, planes);
  const double* mass = p.mass.data();
  const std::uint8_t* flags = p.flags.data();
  double* density = p.density.data();
  const std::uint64_t* offsets = pairs.offsets.data();
  const std::uint64_t* ends = pairs.ends_of();
  const std::uint32_t* neighbours = pairs.neighbours.data();
  const bool wide = wide_lanes && detail::processor_has_avx2();

#pragma omp parallel
  {
    detail::PairScratch scratch;
#pragma omp for schedule(dynamic, 128)
    for (std::int64_t ii = 0; ii < n; ++ii) {
      const auto i = static_cast<std::size_t>(ii);
      if ((flags[i] & (particle_fixed | particle_ejected)) != 0) continue;
      const PairCentre centre = detail::pair_centre(frame, i);
      const double pairs_sum = wide ? pair_sum_wide<Kernel, mirrored>(frame, mass, neighbours, offsets[i],
                                                                      ends[i], centre, scratch)
                                    : pair_sum_baseline<Kernel, mirrored>(frame, mass, neighbours, offsets[i],
                                                                          ends[i], centre, scratch);
      density[i] = mass[i] * Kernel::value(0.0, centre.h) + pairs_sum;
    }
  }
}

}  // namespace

void compute_summation_density(Particles& particles, const PairList& pairs, KernelType kernel,
                               const std::array<double, 3>& period, const MirrorPlanes& mirror,
                               bool wide_lanes) {
  with_kernel(kernel, [&](auto k) {
    if (mirror.any()) {
      summation_impl<decltype(k), true>(particles, pairs, period, mirror, wide_lanes);
    } else {
      summation_impl<decltype(k), false>(particles, pairs, period, mirror, wide_lanes);
    }
  });
}

std::string_view density_method_name(DensityMethod method) noexcept {
  return method == DensityMethod::summation ? "summation" : "continuity";
}

}  // namespace craterkit::sph
