#pragma once
// Exact solution of the Riemann problem for an ideal gas (Toro 2009, "Riemann Solvers and Numerical
// Methods for Fluid Dynamics", 3rd ed., chapter 4): the star-region pressure from the pressure
// function f(p) = f_L(p) + f_R(p) + (u_R - u_L) = 0 (eqs. 4.5-4.7, solved with GSL's Brent
// bracketing), the star velocity (eq. 4.9), the star densities (eqs. 4.19, 4.23, 4.32, 4.34) and the
// self-similar solution sampled at x/t (section 4.5).
namespace craterkit::test_support {

struct GasState {
  double density;
  double velocity;
  double pressure;
};

struct RiemannStar {
  double pressure;       // p*
  double velocity;       // u*
  double density_left;   // rho*_L, left of the contact
  double density_right;  // rho*_R, right of the contact
};

class ExactRiemannSolver {
 public:
  // Throws std::invalid_argument for gamma <= 1 or non-positive density/pressure, and
  // std::domain_error when the data generate a vacuum (u_R - u_L >= 2 (c_L + c_R)/(gamma - 1)).
  ExactRiemannSolver(double gamma, const GasState& left, const GasState& right);

  [[nodiscard]] const RiemannStar& star() const { return star_; }

  // The solution at x/t, the initial discontinuity at x = 0, t > 0 (section 4.5).
  [[nodiscard]] GasState sample(double x_over_t) const;

 private:
  double gamma_;
  GasState left_, right_;
  double sound_left_, sound_right_;
  RiemannStar star_{};
};

}  // namespace craterkit::test_support
