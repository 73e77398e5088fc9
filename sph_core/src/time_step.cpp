#include "craterkit/sph/time_step.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace craterkit::sph {

double TimeStepLimits::step(double max_step) const {
  return std::min({courant, acceleration, density, energy, velocity, max_step});
}

TimeStepLimits time_step_limits(const Particles& p, const RateSummary& rates,
                                const TimeStepParameters& params) {
  const auto n = static_cast<std::int64_t>(p.size());
  const double inf = std::numeric_limits<double>::infinity();
  double acceleration = inf, density = inf, energy = inf, velocity = inf;
  const bool limit_velocity = params.velocity_change > 0.0;
  const bool limit_energy = params.energy_change > 0.0 && params.energy_floor > 0.0;
#pragma omp parallel for schedule(static) reduction(min : acceleration, density, energy, velocity)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if ((p.flags[i] & (particle_fixed | particle_ejected)) != 0) continue;
    const double a2 = p.acceleration_x[i] * p.acceleration_x[i] + p.acceleration_y[i] * p.acceleration_y[i] +
                      p.acceleration_z[i] * p.acceleration_z[i];
    if (a2 > 0.0) acceleration = std::min(acceleration, std::sqrt(p.smoothing_length[i] / std::sqrt(a2)));
    if (limit_velocity && a2 > 0.0) {
      const double speed =
          p.sound_speed[i] + std::sqrt(p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
      velocity = std::min(velocity, speed / std::sqrt(a2));
    }
    const double drho = std::abs(p.density_rate[i]);
    if (drho > 0.0) density = std::min(density, p.density[i] / drho);
    const double du = std::abs(p.energy_rate[i]);
    if (limit_energy && du > 0.0) {
      energy = std::min(energy, (std::abs(p.specific_energy[i]) + params.energy_floor) / du);
    }
  }
  TimeStepLimits limits;
  limits.courant = params.courant * rates.min_signal_time;
  limits.acceleration = params.acceleration_factor * acceleration;
  limits.density = params.density_change * density;
  limits.energy = params.energy_change * energy;
  limits.velocity = params.velocity_change * velocity;
  return limits;
}

}  // namespace craterkit::sph
