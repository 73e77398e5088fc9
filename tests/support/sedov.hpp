#pragma once
// Sedov-Taylor point blast in 3D (spherical) into a uniform, cold ideal gas (Sedov 1959; Taylor 1950):
// shock radius r_s = xi0 (E t^2 / rho0)^(1/5) and the self-similar profiles behind the shock.
//
// Method: with D = dr_s/dt = (2/5) r_s/t, xi = r/r_s and u = D phi(xi), rho = rho0 psi(xi),
// p = rho0 D^2 pi(xi), the Euler equations reduce to three ODEs in xi (w = phi - xi):
//   w psi' + psi phi' = -2 psi phi/xi,   w phi' + pi'/psi = (3/2) phi,   w pi' - gamma (pi/psi) w psi' = 3
//   pi,
// integrated (GSL rk8pd, in ln xi) inward from the strong-shock Rankine-Hugoniot state at xi = 1,
// psi = (gamma+1)/(gamma-1), phi = pi = 2/(gamma+1). Energy conservation,
// E = 4 pi r_s^3 rho0 D^2 I with I = int_0^1 (psi phi^2/2 + pi/(gamma-1)) xi^2 dxi, gives
// xi0 = (25 / (16 pi I))^(1/5) (1.15167 for gamma = 5/3, 1.0328 for gamma = 1.4). Near the centre
// (xi < 1e-3) the profiles follow their asymptotic power laws (see sedov.cpp).
#include <vector>

namespace craterkit::test_support {

struct SedovState {
  double density;
  double velocity;  // radial
  double pressure;
};

class SedovSolution {
 public:
  // gamma in (1, 3]; throws std::invalid_argument otherwise.
  explicit SedovSolution(double gamma);

  [[nodiscard]] double gamma() const { return gamma_; }
  [[nodiscard]] double xi0() const { return xi0_; }

  // r_s = xi0 (E t^2 / rho0)^(1/5).
  [[nodiscard]] double shock_radius(double energy, double ambient_density, double time) const;

  // State at radius r and time t > 0 (ambient gas at rest with zero pressure outside r_s).
  [[nodiscard]] SedovState state(double radius, double energy, double ambient_density, double time) const;

  // Dimensionless profiles psi, phi, pi at xi = r/r_s in [0, 1] (the values just behind the shock at 1).
  [[nodiscard]] double density_ratio(double xi) const;   // psi = rho/rho0
  [[nodiscard]] double velocity_ratio(double xi) const;  // phi = u/D
  [[nodiscard]] double pressure_ratio(double xi) const;  // pi = p/(rho0 D^2)

 private:
  double gamma_;
  double xi0_ = 0.0;
  std::vector<double> xi_, psi_, phi_, pi_;  // ascending xi
  [[nodiscard]] double interpolate(const std::vector<double>& values, double xi,
                                   double centre_exponent) const;
};

}  // namespace craterkit::test_support
