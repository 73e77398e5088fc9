#pragma once
// Second-order time integration: the kick-drift-kick leapfrog with a predicted velocity and state
// for the force evaluation (as in Phantom, Price et al. 2018, eqs. 68-72), one rate evaluation per
// step. With the rates r^n of the state at t^n stored in the particles:
//
//   predict:  v^{n+1/2} = v^n + dt/2 a^n,  x^{n+1} = x^n + dt v^{n+1/2},
//             state used for the new rates: v* = v^n + dt a^n, rho* = rho^n + dt drho^n,
//             u* = u^n + dt du^n, alpha* = alpha^n + dt dalpha^n, S* = S^n + dt dS^n,
//             eps* = eps^n + dt deps^n, alpha_d* = alpha_d^n + dt dalpha_d^n (deviatoric stress,
//             total strain and P-alpha distention alpha_d; solid group only)
//   (rates r^{n+1} evaluated at x^{n+1} and the predicted state)
//   correct:  q^{n+1} = q* + dt/2 (r^{n+1} - r^n)   for q = v, rho, u, alpha, S, eps, alpha_d
//             (= q^n + dt/2 (r^n + r^{n+1}): trapezoidal, second order; the distention alpha_d is
//             corrected in this second form from the stored alpha_d^n, since alpha_d* may have been
//             returned to the crush curve, stress_rates.hpp)
//
// Fixed and ejected particles are not advanced. The smoothing length follows the density,
// h ~ (m / rho)^(1/3) (docs/physics.md section 1: dh/dt = -(h/3) (drho/dt)/rho, applied as the ratio of
// the cube roots of the densities before and after each update), and is in addition steered
// towards the neighbour number of the lattice, N_target = (4 pi / 3) (2 eta)^3 (58 for eta = 1.2),
// whenever a particle's count leaves the band N_target (1 +- neighbour_band): by the factor
// (1 + (N_target/N)^(1/3))/2 per step, within [0.8, 1.25] (Hernquist & Katz 1989, eq. 2.12). Why:
// with the continuity equation the density of a particle says nothing about how far its
// neighbours are; a hot particle whose surroundings moved away (the centre of the Sedov blast)
// otherwise keeps a small h, loses its neighbours and keeps its energy. Clamped to [h_min, h_max] and to
// at most max_smoothing_ratio eta (m/rho)^(1/3).
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "craterkit/sph/neighbours/neighbour_search.hpp"
#include "craterkit/sph/particles/particle_selection.hpp"
#include "craterkit/sph/particles/particles.hpp"

namespace craterkit::sph {

struct SmoothingLengthParameters {
  double eta = 1.2;                   // h = eta (m/rho)^(1/3): about 58 neighbours within 2h for eta = 1.2
  double min_smoothing_length = 0.0;  // m
  double max_smoothing_length = std::numeric_limits<double>::infinity();  // m
  // h at most this many times eta (m/rho)^(1/3), the particle's own smoothing length at its density: a
  // particle thrown clear of the others (ejecta) keeps its density and loses its neighbours, and the
  // neighbour-number steering would grow its h without bound (impacts: 3, per particle, whatever the
  // local spacing of a graded target).
  double max_smoothing_ratio = std::numeric_limits<double>::infinity();
  double neighbour_band = 0.25;  // relative deviation of the neighbour count tolerated without steering
};

// The rates of step n, kept between predict() and correct() (the solid-mechanics rates only when
// the particles hold the solid group).
struct IntegratorWorkspace {
  std::vector<double> acceleration_x, acceleration_y, acceleration_z, density_rate, energy_rate,
      viscosity_alpha_rate, stress_rate_xx, stress_rate_xy, stress_rate_xz, stress_rate_yy, stress_rate_yz,
      total_strain_rate, distention_rate;
  std::vector<double> distention;  // alpha_d^n (solid group only): the corrected alpha_d never exceeds it

  // Every array (one entry per particle or none), for code that moves the particles' entries.
  template <class Visit>
  void for_each_array(Visit&& visit) {
    for (auto* values : {&acceleration_x, &acceleration_y, &acceleration_z, &density_rate, &energy_rate,
                         &viscosity_alpha_rate, &stress_rate_xx, &stress_rate_xy, &stress_rate_xz,
                         &stress_rate_yy, &stress_rate_yz, &total_strain_rate, &distention_rate, &distention})
      visit(*values);
  }
};

// Kick, drift (positions wrapped into the box on periodic axes) and predicted state:
// begin_step() for every particle, then drift() over dt.
void predict(Particles& particles, double dt, const Box& box, IntegratorWorkspace& workspace,
             const SmoothingLengthParameters& smoothing);

// The start of a step for the selected particles: their rates r^n (and distention alpha_d^n) are kept
// in the workspace for the correction at the end of their step.
void begin_step(const Particles& particles, IntegratorWorkspace& workspace,
                const ParticleSelection& selection);

// Advances every moving particle by dt along its step's extrapolation with the rates stored in the
// particles (those of its step's start): x += dt (v + dt/2 a), v += dt a, q += dt dq/dt. Applied in
// pieces dt1, dt2, ... it composes exactly to the KDK drift over dt1 + dt2 + ... (x = x^n + t v^n +
// t^2/2 a^n), so with block time steps (block_time_steps.hpp) every particle is at its predicted state
// at every substep, whether or not its own step ends there.
void drift(Particles& particles, double dt, const Box& box, const SmoothingLengthParameters& smoothing);
// A time (s) for which drift() keeps particle i within `room` (m) of where it is now, counting the growth
// of its smoothing length: |x(t) - x(0)| + max(0, h(t) - h(0)) <= room for t below it. A lower bound, from
// the exact parabola of its step's drift (|v| t + |a| t^2 / 2) and its density's linear change; 0 when the
// room is not positive.
[[nodiscard]] double drift_time_within(const Particles& particles, std::size_t i, double room);

// Trapezoidal correction with the rates evaluated after predict().
// neighbour_count: pairs per particle from the rate pass after predict() (RateWorkspace).
// integrate_density: false when the density was summed at the step's final positions
// (summation_density.hpp; positions are final after predict()), which the correction must keep.
void correct(Particles& particles, double dt, const IntegratorWorkspace& workspace,
             std::span<const std::uint32_t> neighbour_count, const SmoothingLengthParameters& smoothing,
             bool integrate_density = true);
// The same for the selected particles, each with its own step (step_of_particle[i], s).
void correct(Particles& particles, std::span<const double> step_of_particle,
             const ParticleSelection& selection, const IntegratorWorkspace& workspace,
             std::span<const std::uint32_t> neighbour_count, const SmoothingLengthParameters& smoothing,
             bool integrate_density = true);

// h = eta (m/rho)^(1/3), clamped, for every particle that is not fixed.
void update_smoothing_length(Particles& particles, const SmoothingLengthParameters& smoothing);

}  // namespace craterkit::sph
