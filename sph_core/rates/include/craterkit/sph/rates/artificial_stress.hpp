#pragma once
// Artificial stress against the tensile instability of SPH (Swegle, Hicks & Attaway 1995): where the
// stress is tensile, particles of a lattice attract each other and clump into pairs and strings. Monaghan
// (2000, JCP 159, 290) and Gray, Monaghan & Swift (2001, CMAME 190, 6641) add a small repulsive stress
// between close neighbours in tension:
//
//   dv_i/dt += sum_j m_j f_ij^n (R_i + R_j) . grad_i W_ij,   f_ij = W(r_ij) / W(dp),   n = 4,
//
// with dp the particle spacing (here h_ij / eta, h = eta dp of a lattice) and R_i built in the frame of the
// principal stresses sigma'_a of sigma_i = S_i - P_i I (Gray et al. 2001, eqs. 27-29):
//
//   R'_aa = -epsilon sigma'_aa / rho_i^2   if sigma'_aa > 0 (tension),   0 otherwise,
//
// rotated back to x, y, z. f_ij is 1 at the spacing of the lattice and grows as neighbours come closer
// (f_ij^4 = 5e-3 at 1.5 spacings for the cubic spline with h = 1.2 dp), so the repulsion acts mostly
// between neighbours that came closer than their spacing. Gray et al. use epsilon = 0.3 for
// solids. The pair term has the form of the stress force (rates.hpp), so the pair forces cancel and its
// work enters the energy equation as that of the stress: momentum and total energy are conserved.
//
// Off by default: the impact targets are granular (no tensile strength beyond a cohesion of 0-1 Pa) and
// the elastic tests run in the linear regime; docs/strength_and_porosity.md says when to turn it on.
#include <array>

namespace craterkit::sph {

struct ArtificialStress {
  double epsilon = 0.0;  // 0: off; Gray et al. (2001) use 0.3
  // Particle spacing in units of the smoothing length (1/eta of SmoothingLengthParameters): f_ij = 1 at
  // r = h_ij / eta. Set by the simulation from the kernel section.
  double spacing_over_h = 1.0 / 1.2;
  [[nodiscard]] bool on() const noexcept { return epsilon > 0.0; }
};

// The exponent n of f_ij^n (Monaghan 2000 recommends 4 for the cubic spline; Gray et al. use 4).
inline constexpr int artificial_stress_exponent = 4;

// R of one particle (xx, xy, xz, yy, yz, zz) from its total stress sigma (xx, xy, xz, yy, yz, zz), Pa, and
// 1/rho^2. Zero when no principal stress is tensile (checked first, without the eigen decomposition).
[[nodiscard]] std::array<double, 6> artificial_stress_tensor(const std::array<double, 6>& sigma,
                                                             double inverse_density_squared, double epsilon);

}  // namespace craterkit::sph
