#pragma once
// Adaptive global time step (physics.md section 1):
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
// part comes from the rate pass (RateSummary::min_signal_time), which already has max|mu| per particle.
#include <limits>

#include "craterkit/sph/particles.hpp"
#include "craterkit/sph/rates.hpp"

namespace craterkit::sph {

struct TimeStepParameters {
  double courant = 0.3;               // C
  double acceleration_factor = 0.25;  // C_a
  double density_change = 0.05;       // k_rho (largest relative density change per step)
  double energy_change = 0.3;         // k_u; 0 disables the energy limit
  double energy_floor = 0.0;          // u_floor, J/kg; the energy limit applies only when > 0
  double velocity_change = 0.0;       // k_v; 0 disables the velocity-change limit
  double max_step = std::numeric_limits<double>::infinity();  // s
};

struct TimeStepLimits {
  double courant = std::numeric_limits<double>::infinity();
  double acceleration = std::numeric_limits<double>::infinity();
  double density = std::numeric_limits<double>::infinity();
  double energy = std::numeric_limits<double>::infinity();
  double velocity = std::numeric_limits<double>::infinity();
  [[nodiscard]] double step(double max_step) const;  // the smallest, capped at max_step
};

// The limits over the active (neither fixed nor ejected) particles; the rates must be current.
TimeStepLimits time_step_limits(const Particles& particles, const RateSummary& rates,
                                const TimeStepParameters& parameters);

}  // namespace craterkit::sph
