#pragma once
// SPH smoothing kernels in 3D, both with compact support 2h (q = r/h < 2).
//
// Pairs use the kernel evaluated at the mean smoothing length hbar = (h_i + h_j)/2 (docs/physics.md
// section 1, "W at the mean h"), so the pair support is r < h_i + h_j, the same symmetric criterion
// the neighbour search uses, and W_ij = W_ji exactly: the pair forces are antisymmetric.
//
// Each kernel is a small struct with static inline members so that the pair loop is instantiated
// per kernel (a template parameter chosen once per step), never dispatched per pair.
#include <cmath>
#include <numbers>
#include <string_view>

namespace craterkit::sph {

enum class KernelType { cubic_spline, wendland_c2 };

// Cubic B-spline M4 (Monaghan & Lattanzio 1985), normalisation 1/(pi h^3) in 3D:
//   W = sigma [1 - 1.5 q^2 + 0.75 q^3]  for 0 <= q < 1
//   W = sigma 0.25 (2 - q)^3            for 1 <= q < 2.
struct CubicSpline {
  static constexpr KernelType type = KernelType::cubic_spline;
  static constexpr double support = 2.0;  // in units of h

  [[nodiscard]] static double value(double r, double h) noexcept {
    const double q = r / h;
    const double sigma = 1.0 / (std::numbers::pi * h * h * h);
    if (q < 1.0) return sigma * (1.0 - 1.5 * q * q + 0.75 * q * q * q);
    if (q < 2.0) {
      const double t = 2.0 - q;
      return sigma * 0.25 * t * t * t;
    }
    return 0.0;
  }

  // dW/dr (<= 0).
  [[nodiscard]] static double derivative(double r, double h) noexcept {
    const double q = r / h;
    const double sigma = 1.0 / (std::numbers::pi * h * h * h * h);
    if (q < 1.0) return sigma * (-3.0 * q + 2.25 * q * q);
    if (q < 2.0) {
      const double t = 2.0 - q;
      return -sigma * 0.75 * t * t;
    }
    return 0.0;
  }
};

// Wendland C2 (Wendland 1995; Dehnen & Aly 2012, table 1) rescaled to support 2h:
//   W = 21/(16 pi h^3) (1 - q/2)^4 (1 + 2q)  for 0 <= q < 2.
// Free of the pairing instability, smoother density estimates at high neighbour numbers.
struct WendlandC2 {
  static constexpr KernelType type = KernelType::wendland_c2;
  static constexpr double support = 2.0;

  [[nodiscard]] static double value(double r, double h) noexcept {
    const double q = r / h;
    if (q >= 2.0) return 0.0;
    const double sigma = 21.0 / (16.0 * std::numbers::pi * h * h * h);
    const double t = 1.0 - 0.5 * q;
    const double t2 = t * t;
    return sigma * t2 * t2 * (1.0 + 2.0 * q);
  }

  // dW/dr = sigma/h * d/dq[(1-q/2)^4 (1+2q)] = sigma/h * (-5 q (1-q/2)^3).
  [[nodiscard]] static double derivative(double r, double h) noexcept {
    const double q = r / h;
    if (q >= 2.0) return 0.0;
    const double sigma = 21.0 / (16.0 * std::numbers::pi * h * h * h * h);
    const double t = 1.0 - 0.5 * q;
    return -5.0 * sigma * q * t * t * t;
  }
};

// Calls f(CubicSpline{}) or f(WendlandC2{}): the single place where the kernel choice is resolved.
template <class F>
decltype(auto) with_kernel(KernelType type, F&& f) {
  switch (type) {
    case KernelType::wendland_c2:
      return f(WendlandC2{});
    case KernelType::cubic_spline:
    default:
      return f(CubicSpline{});
  }
}

[[nodiscard]] inline std::string_view kernel_name(KernelType type) noexcept {
  return type == KernelType::wendland_c2 ? "wendland_c2" : "cubic_spline";
}

}  // namespace craterkit::sph
