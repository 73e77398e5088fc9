#include "support/porous_hugoniot.hpp"

#include <cmath>
#include <stdexcept>

#include "support/root_finding.hpp"

namespace craterkit::test_support {

double porous_initial_density(const sph::EquationOfState& matrix, const sph::PAlphaParameters& crush) {
  const auto reference = sph::solid_reference(matrix);
  if (!reference) throw std::invalid_argument("porous Hugoniot: the matrix law has no reference density");
  return reference->density / crush.initial_distention;
}

PorousHugoniotPoint porous_hugoniot_at_pressure(const sph::EquationOfState& matrix,
                                                const sph::PAlphaParameters& crush, double pressure) {
  if (!(pressure > 0.0)) throw std::invalid_argument("porous_hugoniot_at_pressure: pressure must be > 0");
  const double rho1 = porous_initial_density(matrix, crush);
  const double alpha = sph::crush_curve_distention(crush, pressure);
  const auto energy = [&](double rho) { return 0.5 * pressure * (1.0 / rho1 - 1.0 / rho); };
  const auto residual = [&](double rho) {
    return sph::evaluate(matrix, alpha * rho, energy(rho)).pressure / alpha - pressure;
  };
  // residual(rho1) = P_m(alpha rho1, 0)/alpha - P < 0 since alpha rho1 <= rho_m0; grow the upper end.
  double upper = 2.0 * rho1;
  for (int expansions = 0; residual(upper) <= 0.0; ++expansions) {
    if (expansions > 60) throw std::domain_error("porous_hugoniot_at_pressure: no shocked density found");
    upper *= 2.0;
  }
  const double rho = brent_root(residual, rho1, upper);
  const double up = std::sqrt(pressure * (1.0 / rho1 - 1.0 / rho));
  return PorousHugoniotPoint{rho, energy(rho), pressure, alpha, up, rho * up / (rho - rho1)};
}

PorousHugoniotPoint porous_hugoniot_at_particle_velocity(const sph::EquationOfState& matrix,
                                                         const sph::PAlphaParameters& crush,
                                                         double particle_velocity) {
  if (!(particle_velocity > 0.0)) {
    throw std::invalid_argument("porous_hugoniot_at_particle_velocity: particle velocity must be > 0");
  }
  const auto mismatch = [&](double p) {
    return porous_hugoniot_at_pressure(matrix, crush, p).particle_velocity - particle_velocity;
  };
  // u_p grows with P: bracket by geometric growth from a pressure far below any of interest.
  double lower = 1.0;  // Pa
  if (mismatch(lower) > 0.0)
    throw std::domain_error("porous Hugoniot: particle velocity below the 1 Pa state");
  double upper = 2.0 * lower;
  while (mismatch(upper) <= 0.0) {
    lower = upper;
    upper *= 2.0;
    if (upper > 1e15) throw std::domain_error("porous Hugoniot: no pressure reaches this particle velocity");
  }
  return porous_hugoniot_at_pressure(matrix, crush, brent_root(mismatch, lower, upper));
}

PorousImpedanceMatch porous_impedance_match(const sph::EquationOfState& projectile,
                                            const InitialState& projectile_initial,
                                            const sph::EquationOfState& target_matrix,
                                            const sph::PAlphaParameters& target_crush, double impact_speed) {
  if (!(impact_speed > 0.0)) throw std::invalid_argument("porous_impedance_match: impact speed must be > 0");
  const auto target_pressure = [&](double u) {
    return u > 0.0 ? porous_hugoniot_at_particle_velocity(target_matrix, target_crush, u).pressure : 0.0;
  };
  const auto mismatch = [&](double u) {
    return target_pressure(u) -
           hugoniot_at_particle_velocity(projectile, projectile_initial, impact_speed - u).pressure;
  };
  const double u = brent_root(mismatch, 0.0, impact_speed);
  PorousImpedanceMatch match{};
  match.particle_velocity = u;
  match.target = porous_hugoniot_at_particle_velocity(target_matrix, target_crush, u);
  match.projectile = hugoniot_at_particle_velocity(projectile, projectile_initial, impact_speed - u);
  match.pressure = match.target.pressure;
  return match;
}

}  // namespace craterkit::test_support
