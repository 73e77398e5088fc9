#include "craterkit/sph/solver/ejecta.hpp"

#include <cstdio>

namespace craterkit::sph {

EjectaRecord ejecta_record(const Particles& p, std::size_t i, double time, std::uint64_t step) {
  return {p.id[i], p.material[i], p.mass[i], time, step, p.x[i], p.y[i], p.z[i], p.vx[i], p.vy[i], p.vz[i]};
}

std::size_t eject_particles(Particles& p, const EjectionRule& rule,
                            std::span<const std::uint32_t> neighbour_count, double time, std::uint64_t step,
                            std::vector<EjectaRecord>& out) {
  if (!(rule.radius > 0.0)) return 0;
  const double r2 = rule.radius * rule.radius;
  const double v2 = rule.escape_speed * rule.escape_speed;
  const bool escape_rule = rule.escape_speed > 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if ((p.flags[i] & (particle_fixed | particle_ejected)) != 0 || !(p.z[i] > 0.0)) continue;
    const bool left = p.x[i] * p.x[i] + p.y[i] * p.y[i] + p.z[i] * p.z[i] > r2;
    const bool escaping = escape_rule && p.vz[i] > 0.0 && i < neighbour_count.size() &&
                          neighbour_count[i] == 0 &&
                          p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i] > v2;
    if (!left && !escaping) continue;
    p.flags[i] |= particle_ejected;
    // Out of the hydrodynamics: no rates from now on (the integrator no longer reads them).
    p.acceleration_x[i] = p.acceleration_y[i] = p.acceleration_z[i] = 0.0;
    p.density_rate[i] = p.energy_rate[i] = p.viscosity_alpha_rate[i] = 0.0;
    if (p.solid_fields) {
      p.stress_rate_xx[i] = p.stress_rate_xy[i] = p.stress_rate_xz[i] = 0.0;
      p.stress_rate_yy[i] = p.stress_rate_yz[i] = p.total_strain_rate[i] = p.distention_rate[i] = 0.0;
    }
    out.push_back(ejecta_record(p, i, time, step));
    ++count;
  }
  return count;
}

std::vector<std::uint32_t> ejected_last_order(const Particles& p, std::size_t* active) {
  std::vector<std::uint32_t> order;
  order.reserve(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    if ((p.flags[i] & particle_ejected) == 0) order.push_back(static_cast<std::uint32_t>(i));
  }
  *active = order.size();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if ((p.flags[i] & particle_ejected) != 0) order.push_back(static_cast<std::uint32_t>(i));
  }
  return order;
}

}  // namespace craterkit::sph
