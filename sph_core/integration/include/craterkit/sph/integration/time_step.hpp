#pragma once
// Adaptive global time step (docs/physics.md section 1):
//   dt = min over active particles of
//        C   h / (c + 1.2 (alpha c + beta max|mu|))   (Courant, with the viscous signal speed),
//        C_a sqrt(h / |a|)                            (acceleration),
//        k_rho rho / |drho/dt|                        (relative density change per step),
//        k_u (|u| + u_floor) / |du/dt|                (relative energy change, with a floor so that
//                                                      a cold particle does not force dt to zero),
//        k_v (c + |v|) / |a|                          (velocity change per step; 0 disables it),
// capped at max_step. The velocity-change limit is for pairs of very different mass (the light
// point-source stand-in projectile of an impact, impact_setup.hpp, against target particles 100 to 1000
// times heavier): the viscous force on the light particle then stops it on a time far below h/c and
// below sqrt(h/|a|) (the drag's time is |v|/|a|), and an explicit step longer than that overshoots and
// blows up (docs/impact_setup.md, "Time step"). For particles of similar mass it does not bind. The Courant
// part comes from the rate pass (RateWorkspace::signal_time), which already has max|mu| per particle.
#include <cstddef>
#include <limits>
#include <span>

#include "craterkit/sph/particles/particle_selection.hpp"
#include "craterkit/sph/particles/particles.hpp"
#include "craterkit/sph/rates/rates.hpp"

namespace craterkit::sph {

struct TimeStepParameters {
  double courant = 0.3;               // C
  double acceleration_factor = 0.25;  // C_a
  double density_change = 0.05;       // k_rho (largest relative density change per step)
  double energy_change = 0.3;         // k_u; 0 disables the energy limit
  double energy_floor = 0.0;          // u_floor, J/kg; the energy limit applies only when > 0
  double velocity_change = 0.0;       // k_v; 0 disables the velocity-change limit
  double max_step = std::numeric_limits<double>::infinity();  // s
  // Block time steps (block_time_steps.hpp): 0 = one global step; N > 0 = particles take power-of-two
  // fractions of a block that is at most 2^N times the shortest particle step.
  int block_levels = 0;
};

struct TimeStepLimits {
  double courant = std::numeric_limits<double>::infinity();
  double acceleration = std::numeric_limits<double>::infinity();
  double density = std::numeric_limits<double>::infinity();
  double energy = std::numeric_limits<double>::infinity();
  double velocity = std::numeric_limits<double>::infinity();
  [[nodiscard]] double step(double max_step) const;  // the smallest, capped at max_step
};

// For each selected moving particle: its own limits (particle_time_step_limits) and
// Particles::time_step = their smallest, capped at max_step (+infinity for fixed and ejected particles);
// returns each limit's minimum over the selection (the global step's limits when all are selected). The
// rates and signal_time (RateWorkspace::signal_time) must be those of the particles' last evaluation.
TimeStepLimits update_time_steps(Particles& particles, std::span<const double> signal_time,
                                 const TimeStepParameters& parameters, const ParticleSelection& selection);

// The same limits for particle i alone, from its own rates and its signal time h_i / signal_i
// (RateWorkspace::signal_time): the step it may take with block time steps (block_time_steps.hpp).
TimeStepLimits particle_time_step_limits(const Particles& particles, std::size_t i, double signal_time,
                                         const TimeStepParameters& parameters);

}  // namespace craterkit::sph
