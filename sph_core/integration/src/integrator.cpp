#include "craterkit/sph/integration/integrator.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "craterkit/sph/integration/cube_root_near_one.hpp"

namespace craterkit::sph {

namespace {

inline bool moves(std::uint8_t flags) {
  return (flags & (particle_fixed | particle_ejected)) == 0;
}

inline double smoothing_length_of(double mass, double density, const SmoothingLengthParameters& s) {
  const double h = s.eta * std::cbrt(mass / density);
  return std::clamp(h, s.min_smoothing_length, s.max_smoothing_length);
}

// h clamped to [h_min, h_max] and to max_smoothing_ratio times eta (m/rho)^(1/3).
inline double clamped_smoothing_length(double h, double mass, double density,
                                       const SmoothingLengthParameters& s) {
  if (s.max_smoothing_ratio < std::numeric_limits<double>::infinity()) {
    // The cube root is taken only where the cap can bind: below 0.99 of the cap cubed (h at most 0.997 of
    // it) min() returns h whatever the last bit of cbrt, so the result is the same (a cube root per particle
    // and drift was 3 % of an SCI run).
    const double cap_factor = s.max_smoothing_ratio * s.eta;
    const double cap_cubed = cap_factor * cap_factor * cap_factor * (mass / density);
    if (!(h * h * h < 0.99 * cap_cubed)) h = std::min(h, cap_factor * std::cbrt(mass / density));
  }
  return std::clamp(h, s.min_smoothing_length, s.max_smoothing_length);
}

template <class StepOf>
void correct_selected(Particles& p, StepOf step_of, const ParticleSelection& selection,
                      const IntegratorWorkspace& w, std::span<const std::uint32_t> neighbour_count,
                      const SmoothingLengthParameters& smoothing, bool integrate_density) {
  const auto n = static_cast<std::int64_t>(selection.size());
  const double eta2 = 2.0 * smoothing.eta;
  const double target = 4.0 / 3.0 * 3.14159265358979323846 * eta2 * eta2 * eta2;
  const double low = target * (1.0 - smoothing.neighbour_band),
               high = target * (1.0 + smoothing.neighbour_band);
  const bool solid = p.solid_fields;
#pragma omp parallel for schedule(static)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = selection.at(static_cast<std::size_t>(ii));
    if (!moves(p.flags[i])) continue;
    const double half = 0.5 * step_of(i);
    p.vx[i] += half * (p.acceleration_x[i] - w.acceleration_x[i]);
    p.vy[i] += half * (p.acceleration_y[i] - w.acceleration_y[i]);
    p.vz[i] += half * (p.acceleration_z[i] - w.acceleration_z[i]);
    const double density = p.density[i];
    if (integrate_density) p.density[i] += half * (p.density_rate[i] - w.density_rate[i]);
    p.specific_energy[i] += half * (p.energy_rate[i] - w.energy_rate[i]);
    p.viscosity_alpha[i] += half * (p.viscosity_alpha_rate[i] - w.viscosity_alpha_rate[i]);
    if (solid) {
      p.stress_xx[i] += half * (p.stress_rate_xx[i] - w.stress_rate_xx[i]);
      p.stress_xy[i] += half * (p.stress_rate_xy[i] - w.stress_rate_xy[i]);
      p.stress_xz[i] += half * (p.stress_rate_xz[i] - w.stress_rate_xz[i]);
      p.stress_yy[i] += half * (p.stress_rate_yy[i] - w.stress_rate_yy[i]);
      p.stress_yz[i] += half * (p.stress_rate_yz[i] - w.stress_rate_yz[i]);
      p.total_strain[i] += half * (p.total_strain_rate[i] - w.total_strain_rate[i]);
      // alpha^{n+1} = alpha^n + dt/2 (r^n + r^{n+1}) <= alpha^n (both rates <= 0), from the stored alpha^n
      // rather than from alpha*: the per-particle phase may have returned alpha* to the crush curve to
      // evaluate the predicted pressure, and adding dt/2 (r^{n+1} - r^n) to a returned alpha* would count
      // the step's compaction twice. The clamp makes "never re-expands" exact also after rounding.
      p.distention[i] = std::clamp(w.distention[i] + half * (w.distention_rate[i] + p.distention_rate[i]),
                                   1.0, w.distention[i]);
    }
    double factor = cube_root_near_one(density / p.density[i]);
    const double count = neighbour_count[i];
    if (count < low || count > high) {
      factor *= std::clamp(0.5 * (1.0 + std::cbrt(target / std::max(count, 1.0))), 0.8, 1.25);
    }
    p.smoothing_length[i] =
        clamped_smoothing_length(p.smoothing_length[i] * factor, p.mass[i], p.density[i], smoothing);
  }
}

}  // namespace

void update_smoothing_length(Particles& p, const SmoothingLengthParameters& smoothing) {
  const auto n = static_cast<std::int64_t>(p.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if ((p.flags[i] & particle_fixed) != 0) continue;
    p.smoothing_length[i] = smoothing_length_of(p.mass[i], p.density[i], smoothing);
  }
}

void begin_step(const Particles& p, IntegratorWorkspace& w, const ParticleSelection& selection) {
  const std::size_t count = p.size();
  w.acceleration_x.resize(count);
  w.acceleration_y.resize(count);
  w.acceleration_z.resize(count);
  w.density_rate.resize(count);
  w.energy_rate.resize(count);
  w.viscosity_alpha_rate.resize(count);
  const bool solid = p.solid_fields;
  const std::size_t solid_count = solid ? count : 0;
  w.stress_rate_xx.resize(solid_count);
  w.stress_rate_xy.resize(solid_count);
  w.stress_rate_xz.resize(solid_count);
  w.stress_rate_yy.resize(solid_count);
  w.stress_rate_yz.resize(solid_count);
  w.total_strain_rate.resize(solid_count);
  w.distention_rate.resize(solid_count);
  w.distention.resize(solid_count);
  const auto n = static_cast<std::int64_t>(selection.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = selection.at(static_cast<std::size_t>(ii));
    w.acceleration_x[i] = p.acceleration_x[i];
    w.acceleration_y[i] = p.acceleration_y[i];
    w.acceleration_z[i] = p.acceleration_z[i];
    w.density_rate[i] = p.density_rate[i];
    w.energy_rate[i] = p.energy_rate[i];
    w.viscosity_alpha_rate[i] = p.viscosity_alpha_rate[i];
    if (solid) {
      w.stress_rate_xx[i] = p.stress_rate_xx[i];
      w.stress_rate_xy[i] = p.stress_rate_xy[i];
      w.stress_rate_xz[i] = p.stress_rate_xz[i];
      w.stress_rate_yy[i] = p.stress_rate_yy[i];
      w.stress_rate_yz[i] = p.stress_rate_yz[i];
      w.total_strain_rate[i] = p.total_strain_rate[i];
      w.distention_rate[i] = p.distention_rate[i];
      w.distention[i] = p.distention[i];
    }
  }
}

void drift(Particles& p, double dt, const Box& box, const SmoothingLengthParameters& smoothing) {
  const auto n = static_cast<std::int64_t>(p.size());
  const bool solid = p.solid_fields;
  const double half = 0.5 * dt;
#pragma omp parallel for schedule(static)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if (!moves(p.flags[i])) continue;
    const double ax = p.acceleration_x[i], ay = p.acceleration_y[i], az = p.acceleration_z[i];
    p.x[i] = wrap_position(box, 0, p.x[i] + dt * (p.vx[i] + half * ax));
    p.y[i] = wrap_position(box, 1, p.y[i] + dt * (p.vy[i] + half * ay));
    p.z[i] = wrap_position(box, 2, p.z[i] + dt * (p.vz[i] + half * az));
    p.vx[i] += dt * ax;
    p.vy[i] += dt * ay;
    p.vz[i] += dt * az;
    const double density = p.density[i];
    p.density[i] += dt * p.density_rate[i];
    p.specific_energy[i] += dt * p.energy_rate[i];
    p.viscosity_alpha[i] += dt * p.viscosity_alpha_rate[i];
    if (solid) {
      p.stress_xx[i] += dt * p.stress_rate_xx[i];
      p.stress_xy[i] += dt * p.stress_rate_xy[i];
      p.stress_xz[i] += dt * p.stress_rate_xz[i];
      p.stress_yy[i] += dt * p.stress_rate_yy[i];
      p.stress_yz[i] += dt * p.stress_rate_yz[i];
      p.total_strain[i] += dt * p.total_strain_rate[i];
      // dalpha/dt <= 0 (compaction is irreversible); alpha >= 1 (no matrix denser than its law).
      p.distention[i] = std::max(1.0, p.distention[i] + dt * p.distention_rate[i]);
    }
    p.smoothing_length[i] =
        clamped_smoothing_length(p.smoothing_length[i] * cube_root_near_one(density / p.density[i]),
                                 p.mass[i], p.density[i], smoothing);
  }
}

double drift_time_within(const Particles& p, std::size_t i, double room) {
  if (!(room > 0.0)) return 0.0;
  // Half the room for the path, half for the growth of h, less what the rounding of the drifts (which follow
  // the parabola to round-off, half an ulp of each coordinate and of h per drift) may add over a block.
  const double rounding =
      1e-12 * (std::abs(p.x[i]) + std::abs(p.y[i]) + std::abs(p.z[i]) + p.smoothing_length[i]);
  const double half_room = 0.5 * (room - rounding);
  if (!(half_room > 0.0)) return 0.0;
  const double speed = std::sqrt(p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
  const double acceleration =
      std::sqrt(p.acceleration_x[i] * p.acceleration_x[i] + p.acceleration_y[i] * p.acceleration_y[i] +
                p.acceleration_z[i] * p.acceleration_z[i]);
  // The path: |x(t) - x| <= |v| t + |a| t^2 / 2 <= half_room, solved for t in the form without cancellation.
  const double path_time =
      half_room / (0.5 * speed + std::sqrt(0.25 * speed * speed + 0.5 * acceleration * half_room));
  // The growth: rho(t) = rho (1 - s t) with s = -drho/rho > 0, and h(t) <= h (rho / rho(t))^(1/3) (the clamps
  // only lower it), which stays within h + half_room while 1 - s t >= 1 / (1 + half_room / h)^3.
  const double shrink = -p.density_rate[i] / p.density[i];
  if (!(shrink > 0.0)) return path_time;
  const double ratio = 1.0 + half_room / p.smoothing_length[i];
  return std::min(path_time, (1.0 - 1.0 / (ratio * ratio * ratio)) / shrink);
}

void predict(Particles& p, double dt, const Box& box, IntegratorWorkspace& w,
             const SmoothingLengthParameters& smoothing) {
  begin_step(p, w, ParticleSelection::all(p.size()));
  drift(p, dt, box, smoothing);
}

void correct(Particles& p, double dt, const IntegratorWorkspace& w,
             std::span<const std::uint32_t> neighbour_count, const SmoothingLengthParameters& smoothing,
             bool integrate_density) {
  correct_selected(
      p, [dt](std::size_t) { return dt; }, ParticleSelection::all(p.size()), w, neighbour_count, smoothing,
      integrate_density);
}

void correct(Particles& p, std::span<const double> step_of_particle, const ParticleSelection& selection,
             const IntegratorWorkspace& w, std::span<const std::uint32_t> neighbour_count,
             const SmoothingLengthParameters& smoothing, bool integrate_density) {
  correct_selected(
      p, [step_of_particle](std::size_t i) { return step_of_particle[i]; }, selection, w, neighbour_count,
      smoothing, integrate_density);
}

}  // namespace craterkit::sph
