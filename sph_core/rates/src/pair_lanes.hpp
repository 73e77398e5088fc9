#pragma once
// Four pairs at a time: the value types of the pair passes' j-loops (rates.cpp, summation_density.cpp) and
// the kernels on them. Private to the rates layer.
//
// A lane holds one pair; every operation acts on the four lanes alike (GCC's vector extensions, which clang
// also reads). Each lane computes exactly what the one-pair expression computes, in the same order, so a
// pair's terms are those of a scalar loop bit for bit; what changes is the order of the sums over j (four
// partial sums, added in a fixed order at the end). Each j-loop is compiled twice: for AVX2, where a lane
// operation is one 256-bit instruction, and for the baseline x86-64, where it is two 128-bit ones. Both do
// the same IEEE operations (no fused multiply-add: the AVX2 target does not include FMA), so every machine
// gets the same results.
//
// The functions take their vectors by reference and write their results through one: a 256-bit vector
// passed by value would change the calling convention between the two builds (GCC's -Wpsabi).
#include <cstdint>
#include <numbers>

#include "craterkit/sph/particles/kernel.hpp"

namespace craterkit::sph::detail {

// The attribute of the AVX2 build of a j-loop (with [[gnu::noinline]], so that neither build is inlined into
// the other or into the driver), and whether this processor runs it.
#if defined(__x86_64__)
#define CRATERKIT_WIDE_LANES gnu::target("avx2")
[[nodiscard]] inline bool processor_has_avx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}
#else
#define CRATERKIT_WIDE_LANES gnu::noinline
[[nodiscard]] inline bool processor_has_avx2() {
  return false;
}
#endif

inline constexpr int lane_count = 4;
using Lanes = double __attribute__((vector_size(32)));
using LaneMask = std::int64_t __attribute__((vector_size(32)));  // all ones (true) or zero per lane

[[gnu::always_inline]] inline void lane_sqrt(const Lanes& x, Lanes& root) {
  for (int l = 0; l < lane_count; ++l) root[l] = __builtin_sqrt(x[l]);
}

// The four lanes summed in a fixed order.
[[gnu::always_inline]] inline double lane_sum(const Lanes& x) {
  return (x[0] + x[1]) + (x[2] + x[3]);
}

// std::max over the lanes, as a scalar loop over the same values would take it.
[[gnu::always_inline]] inline double lane_max(const Lanes& x, double start) {
  double m = start;
  for (int l = 0; l < lane_count; ++l) m = m < x[l] ? x[l] : m;
  return m;
}

// dW/dr (r, h) per lane: Kernel::derivative written for lanes (kernel.hpp), both pieces computed and the one
// that applies selected.
template <class Kernel>
[[gnu::always_inline]] inline void kernel_derivative(const Lanes& r, const Lanes& h, Lanes& dwdr) {
  const Lanes zero = {0.0, 0.0, 0.0, 0.0};
  const Lanes q = r / h;
  if constexpr (Kernel::type == KernelType::cubic_spline) {
    const Lanes sigma = 1.0 / (std::numbers::pi * h * h * h * h);
    const Lanes t = 2.0 - q;
    dwdr = q < 1.0 ? sigma * (-3.0 * q + 2.25 * q * q) : (q < 2.0 ? -sigma * 0.75 * t * t : zero);
  } else {
    static_assert(Kernel::type == KernelType::wendland_c2);
    const Lanes sigma = 21.0 / (16.0 * std::numbers::pi * h * h * h * h);
    const Lanes t = 1.0 - 0.5 * q;
    dwdr = q >= 2.0 ? zero : -5.0 * sigma * q * t * t * t;
  }
}

// W(r, h) per lane: Kernel::value written for lanes (kernel.hpp), both pieces computed and the one that
// applies selected.
template <class Kernel>
[[gnu::always_inline]] inline void kernel_value(const Lanes& r, const Lanes& h, Lanes& w) {
  const Lanes zero = {0.0, 0.0, 0.0, 0.0};
  const Lanes q = r / h;
  if constexpr (Kernel::type == KernelType::cubic_spline) {
    const Lanes sigma = 1.0 / (std::numbers::pi * h * h * h);
    const Lanes t = 2.0 - q;
    w = q < 1.0 ? sigma * (1.0 - 1.5 * q * q + 0.75 * q * q * q)
                : (q < 2.0 ? sigma * 0.25 * t * t * t : zero);
  } else {
    static_assert(Kernel::type == KernelType::wendland_c2);
    const Lanes sigma = 21.0 / (16.0 * std::numbers::pi * h * h * h);
    const Lanes t = 1.0 - 0.5 * q;
    const Lanes t2 = t * t;
    w = q >= 2.0 ? zero : sigma * t2 * t2 * (1.0 + 2.0 * q);
  }
}

// W(q, 1) per lane (Kernel::value at unit h), for the artificial stress.
template <class Kernel>
[[gnu::always_inline]] inline void kernel_value_at_unit_h(const Lanes& q, Lanes& w) {
  const Lanes zero = {0.0, 0.0, 0.0, 0.0};
  if constexpr (Kernel::type == KernelType::cubic_spline) {
    const double sigma = 1.0 / (std::numbers::pi * 1.0 * 1.0 * 1.0);
    const Lanes t = 2.0 - q;
    w = q < 1.0 ? sigma * (1.0 - 1.5 * q * q + 0.75 * q * q * q)
                : (q < 2.0 ? sigma * 0.25 * t * t * t : zero);
  } else {
    static_assert(Kernel::type == KernelType::wendland_c2);
    const double sigma = 21.0 / (16.0 * std::numbers::pi * 1.0 * 1.0 * 1.0);
    const Lanes t = 1.0 - 0.5 * q;
    const Lanes t2 = t * t;
    w = q >= 2.0 ? zero : sigma * t2 * t2 * (1.0 + 2.0 * q);
  }
}

}  // namespace craterkit::sph::detail
