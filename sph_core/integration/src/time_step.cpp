#include "craterkit/sph/integration/time_step.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace craterkit::sph {

double TimeStepLimits::step(double max_step) const {
  return std::min({courant, acceleration, density, energy, velocity, max_step});
}

TimeStepLimits particle_time_step_limits(const Particles& p, std::size_t i, double signal_time,
                                         const TimeStepParameters& params) {
  TimeStepLimits limits;
  limits.courant = params.courant * signal_time;
  const double a2 = p.acceleration_x[i] * p.acceleration_x[i] + p.acceleration_y[i] * p.acceleration_y[i] +
                    p.acceleration_z[i] * p.acceleration_z[i];
  if (a2 > 0.0) {
    const double a = std::sqrt(a2);
    limits.acceleration = params.acceleration_factor * std::sqrt(p.smoothing_length[i] / a);
    if (params.velocity_change > 0.0) {
      const double speed =
          p.sound_speed[i] + std::sqrt(p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
      limits.velocity = params.velocity_change * (speed / a);
    }
  }
  const double drho = std::abs(p.density_rate[i]);
  if (drho > 0.0) limits.density = params.density_change * (p.density[i] / drho);
  const double du = std::abs(p.energy_rate[i]);
  if (params.energy_change > 0.0 && params.energy_floor > 0.0 && du > 0.0) {
    limits.energy = params.energy_change * ((std::abs(p.specific_energy[i]) + params.energy_floor) / du);
  }
  return limits;
}

TimeStepLimits update_time_steps(Particles& p, std::span<const double> signal_time,
                                 const TimeStepParameters& params, const ParticleSelection& selection) {
  const auto n = static_cast<std::int64_t>(selection.size());
  const double inf = std::numeric_limits<double>::infinity();
  double courant = inf, acceleration = inf, density = inf, energy = inf, velocity = inf;
  p.time_step.resize(p.size(), inf);
#pragma omp parallel for schedule(static) reduction(min : courant, acceleration, density, energy, velocity)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = selection.at(static_cast<std::size_t>(ii));
    if ((p.flags[i] & (particle_fixed | particle_ejected)) != 0) {
      p.time_step[i] = inf;
      continue;
    }
    const TimeStepLimits own = particle_time_step_limits(p, i, signal_time[i], params);
    p.time_step[i] = own.step(params.max_step);
    courant = std::min(courant, own.courant);
    acceleration = std::min(acceleration, own.acceleration);
    density = std::min(density, own.density);
    energy = std::min(energy, own.energy);
    velocity = std::min(velocity, own.velocity);
  }
  return TimeStepLimits{courant, acceleration, density, energy, velocity};
}

}  // namespace craterkit::sph
