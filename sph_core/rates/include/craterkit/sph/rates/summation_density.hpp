#pragma once
// Density by kernel summation (Monaghan 1992, ARA&A 30, 543, eq. 2.6; Price 2012, J. Comput. Phys. 231,
// 759, eq. 5), an alternative to the continuity equation for gases:
//   rho_i = m_i W(0, h_i) + sum_j m_j W(r_ij, hbar_ij),   hbar_ij = (h_i + h_j)/2,
// the same symmetrised kernel and pair support (r < h_i + h_j) as the rate pass (rates.hpp).
//
// Why it exists: the continuity equation carries a particle's density along with it, so the density of
// a particle whose neighbours move away is only as good as the rate that was integrated; in the hot,
// rarefied centre of a point blast that leaves the deposit's particles with too much density and pressure
// (docs/validation.md, Sedov). The summation sees where the neighbours are. It is not for impacts
// (docs/physics.md section 1): at free surfaces it underestimates the density (missing neighbours) and it
// knows nothing of porosity, which is why the continuity equation is the default.
#include <array>
#include <string_view>

#include "craterkit/sph/particles/kernel.hpp"
#include "craterkit/sph/particles/particles.hpp"
#include "craterkit/sph/rates/rates.hpp"

namespace craterkit::sph {

enum class DensityMethod { continuity, summation };

// Overwrites the density of every particle that is neither fixed nor ejected. period: box edge along
// each periodic axis (0: open), for minimum-image distances, as RateOptions::period; mirror: the symmetry
// planes the lists were built with, as RateOptions::mirror (image entries are reflected across them);
// wide_lanes: as RateOptions::wide_lanes (the AVX2 build of the pair sum where the processor has it; the
// baseline build gives the same bits).
void compute_summation_density(Particles& particles, const PairList& pairs, KernelType kernel,
                               const std::array<double, 3>& period, const MirrorPlanes& mirror = {},
                               bool wide_lanes = true);

[[nodiscard]] std::string_view density_method_name(DensityMethod method) noexcept;

}  // namespace craterkit::sph
