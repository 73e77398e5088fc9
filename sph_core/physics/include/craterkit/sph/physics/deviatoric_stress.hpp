#pragma once
// Deviatoric stress kinematics (docs/physics.md section 2, "Strength"): Hooke's law with the Jaumann rate,
// the second invariant, radial return to the yield surface, and the deviatoric strain-rate invariant
// that drives strain weakening. Free functions on plain 3x3 arrays so that the per-particle loop of the
// solver and the independent strain-path driver of the tests call the very same kernels.
//
// Conventions (docs/physics.md section 1): (grad v)_ab = dv_a / dx_b; strain rate eps_dot = sym(grad v);
// rotation rate Omega = (grad v - grad v^T) / 2.
#include <algorithm>
#include <array>
#include <cmath>

namespace craterkit::sph {

using Tensor3 = std::array<std::array<double, 3>, 3>;

// Symmetric traceless deviatoric stress, five independent components (S_zz = -S_xx - S_yy), Pa.
struct DeviatoricStress {
  double xx = 0.0, xy = 0.0, xz = 0.0, yy = 0.0, yz = 0.0;
  [[nodiscard]] double zz() const noexcept { return -xx - yy; }
  [[nodiscard]] Tensor3 full() const noexcept { return {{{xx, xy, xz}, {xy, yy, yz}, {xz, yz, zz()}}}; }
};

// J2 = S:S / 2.
inline double second_invariant(const DeviatoricStress& s) noexcept {
  const double zz = s.zz();
  return 0.5 * (s.xx * s.xx + s.yy * s.yy + zz * zz) + s.xy * s.xy + s.xz * s.xz + s.yz * s.yz;
}

// Jaumann stress rate with Hooke's law (docs/physics.md section 2):
//   dS/dt = 2 G (eps_dot - tr(eps_dot)/3 I) + S Omega^T + Omega S.
inline DeviatoricStress jaumann_stress_rate(const DeviatoricStress& s, const Tensor3& velocity_gradient,
                                            double shear_modulus) noexcept {
  const Tensor3& L = velocity_gradient;
  Tensor3 strain_rate{}, rotation{};
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      strain_rate[a][b] = 0.5 * (L[a][b] + L[b][a]);
      rotation[a][b] = 0.5 * (L[a][b] - L[b][a]);
    }
  }
  const double trace_third = (strain_rate[0][0] + strain_rate[1][1] + strain_rate[2][2]) / 3.0;
  const Tensor3 S = s.full();
  auto rate = [&](int a, int b) {
    double hooke = 2.0 * shear_modulus * (strain_rate[a][b] - (a == b ? trace_third : 0.0));
    double spin = 0.0;
    for (int k = 0; k < 3; ++k)
      spin += S[a][k] * rotation[b][k] + rotation[a][k] * S[k][b];  // S Omega^T + Omega S
    return hooke + spin;
  };
  return {rate(0, 0), rate(0, 1), rate(0, 2), rate(1, 1), rate(1, 2)};
}

// Radial return onto the yield surface: S <- S min(1, Y / sqrt(J2)) (Y compared with sqrt(J2)).
inline DeviatoricStress radial_return(const DeviatoricStress& s, double yield_strength) noexcept {
  const double j2 = second_invariant(s);
  if (j2 <= 0.0) return s;
  const double limit = std::max(0.0, yield_strength);
  const double root = std::sqrt(j2);
  if (root <= limit) return s;
  const double scale = limit / root;
  return {s.xx * scale, s.xy * scale, s.xz * scale, s.yy * scale, s.yz * scale};
}

// sqrt(eps_dot' : eps_dot' / 2), eps_dot' the deviatoric strain rate: the rate at which the
// accumulated total strain grows (our choice for strain weakening; docs/physics.md leaves total or plastic).
inline double deviatoric_strain_rate_invariant(const Tensor3& velocity_gradient) noexcept {
  const Tensor3& L = velocity_gradient;
  const double trace_third = (L[0][0] + L[1][1] + L[2][2]) / 3.0;
  double sum = 0.0;
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      const double e = 0.5 * (L[a][b] + L[b][a]) - (a == b ? trace_third : 0.0);
      sum += e * e;
    }
  }
  return std::sqrt(0.5 * sum);
}

// The rate at which the plastic strain grows, in the measure of deviatoric_strain_rate_invariant(), for a
// stress on the yield surface (the caller decides that it is): the part of the strain rate that would raise
// sqrt(J2) above Y and that the radial return removes. With the Jaumann rate dS/dt = 2 G eps_dot' (+ a
// rotation, which keeps J2), d sqrt(J2)/dt = G (S : eps_dot') / sqrt(J2); the return takes it back as a
// plastic strain of (d sqrt(J2)/dt) / (2 G) per unit time (as sqrt(J2_trial) - Y = 2 G delta eps_p for a
// radial return), so that
//   d eps_p / dt = max(0, S : eps_dot' / (2 sqrt(J2))),
// which for a flow along S (eps_dot' = k S) equals sqrt(eps_dot' : eps_dot' / 2), the total strain rate.
// Zero when unloading (S : eps_dot' < 0) or without stress.
inline double plastic_strain_rate_at_yield(const DeviatoricStress& s,
                                           const Tensor3& velocity_gradient) noexcept {
  const double root = std::sqrt(second_invariant(s));
  if (!(root > 0.0)) return 0.0;
  const Tensor3& L = velocity_gradient;
  // S is traceless, so S : eps_dot' = S : sym(L).
  const double zz = -(s.xx + s.yy);
  const double contraction = s.xx * L[0][0] + s.yy * L[1][1] + zz * L[2][2] + s.xy * (L[0][1] + L[1][0]) +
                             s.xz * (L[0][2] + L[2][0]) + s.yz * (L[1][2] + L[2][1]);
  return std::max(0.0, contraction / (2.0 * root));
}

}  // namespace craterkit::sph
