#include "support/hugoniot.hpp"

#include "support/root_finding.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace craterkit::test_support {
namespace {

double initial_pressure(const sph::EquationOfState& eos, const InitialState& initial) {
  return sph::evaluate(eos, initial.density, initial.specific_energy).pressure;
}

}  // namespace

HugoniotPoint hugoniot_at_density(const sph::EquationOfState& eos, const InitialState& initial,
                                  double density) {
  if (!(density > initial.density)) {
    throw std::invalid_argument("hugoniot_at_density: the shocked density must exceed the initial density");
  }
  const double p1 = initial_pressure(eos, initial);
  const double volume_jump = 1.0 / initial.density - 1.0 / density;
  const auto energy_residual = [&](double e) {
    return e - initial.specific_energy - 0.5 * (sph::evaluate(eos, density, e).pressure + p1) * volume_jump;
  };
  // The residual is negative at E1 under compression (P > 0 there, P1 >= 0) and grows ~linearly in E
  // below the maximum compression; expand the upper end until it turns positive.
  const double lower = initial.specific_energy;
  if (energy_residual(lower) > 0.0) {
    throw std::domain_error("hugoniot_at_density: no compressive shock state (pressure not positive)");
  }
  double step = std::max(1.0, std::abs(sph::evaluate(eos, density, lower).pressure) * volume_jump);
  double upper = lower + step;
  int expansions = 0;
  while (energy_residual(upper) <= 0.0) {
    if (++expansions > 200) {
      throw std::domain_error("hugoniot_at_density: density " + std::to_string(density) +
                              " lies beyond the maximum shock compression of the equation of state");
    }
    step *= 2.0;
    upper = lower + step;
  }
  const double e = brent_root(energy_residual, lower, upper);
  const double p = sph::evaluate(eos, density, e).pressure;
  const double up = std::sqrt(std::max(0.0, (p - p1) * volume_jump));
  return HugoniotPoint{density, e, p, up, density * up / (density - initial.density)};
}

HugoniotPoint hugoniot_at_particle_velocity(const sph::EquationOfState& eos, const InitialState& initial,
                                            double particle_velocity) {
  if (!(particle_velocity >= 0.0)) throw std::invalid_argument("particle velocity must be >= 0");
  const double p1 = initial_pressure(eos, initial);
  if (particle_velocity == 0.0) {
    // Weak-shock limit: U_s -> sqrt(dP/drho along the Hugoniot) = c; report the unshocked state.
    const double c = sph::evaluate(eos, initial.density, initial.specific_energy).sound_speed;
    return HugoniotPoint{initial.density, initial.specific_energy, p1, 0.0, c};
  }
  const auto velocity_residual = [&](double compression) {
    if (compression <= 0.0) return -particle_velocity;  // no shock: u_p = 0
    return hugoniot_at_density(eos, initial, initial.density * (1.0 + compression)).particle_velocity -
           particle_velocity;
  };
  // u_p grows monotonically with the compression rho/rho1 - 1: bracket it by geometric growth.
  double lower = 0.0;
  double upper = 1e-4;
  while (velocity_residual(upper) < 0.0) {
    lower = upper;
    upper *= 1.5;  // hugoniot_at_density throws once beyond the maximum compression
  }
  const double compression = brent_root(velocity_residual, lower, upper);
  return hugoniot_at_density(eos, initial, initial.density * (1.0 + compression));
}

ImpedanceMatch impedance_match(const sph::EquationOfState& projectile, const InitialState& projectile_initial,
                               const sph::EquationOfState& target, const InitialState& target_initial,
                               double impact_speed) {
  if (!(impact_speed > 0.0)) throw std::invalid_argument("impedance_match: impact speed must be > 0");
  const auto pressure_mismatch = [&](double u) {
    return hugoniot_at_particle_velocity(target, target_initial, u).pressure -
           hugoniot_at_particle_velocity(projectile, projectile_initial, impact_speed - u).pressure;
  };
  const double u = brent_root(pressure_mismatch, 0.0, impact_speed);
  ImpedanceMatch match{};
  match.particle_velocity = u;
  match.target = hugoniot_at_particle_velocity(target, target_initial, u);
  match.projectile = hugoniot_at_particle_velocity(projectile, projectile_initial, impact_speed - u);
  match.pressure = match.target.pressure;
  return match;
}

}  // namespace craterkit::test_support
