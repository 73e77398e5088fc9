#pragma once
// Ejecta leaving the simulated domain (docs/physics.md section 4).
//
// Rule (docs/physics.md section 4; docs/impact_setup.md, "Ejecta"): a moving particle (neither fixed nor
// already ejected) above the pre-impact plane (z > 0) is ejected when
//  - it is farther than R_ej from the impact point (the origin), |x| > R_ej with R_ej = R_dom the domain
//    radius: it has left the domain, nothing it meets any more is simulated (the fixed shell ends at R_dom),
//    and on a milligravity body the fraction of it that would fall back lands outside the crater; or
//  - it is faster than the body's escape speed, rising (v_z > 0), and clear of the target, i.e. it had no
//    neighbour within the kernel support in its last rate evaluation: it flies ballistically and never
//    comes back (the engine's constant gravity would bring it back, the body's falling-off gravity does
//    not). A particle falling towards the surface is kept whatever its speed: it will hit it.
// It is flagged particle_ejected and taken out of the hydrodynamics: the
// engine keeps ejected particles at the end of the arrays, outside the neighbour search, the pair loops,
// the time step and the integrator, frozen at their launch state, with their rates zero. Mass, momentum and
// energy stay in the particle set (the conserved-quantity sums include them; a frozen particle keeps its
// kinetic plus potential energy, as a ballistic one in constant gravity would), so target + projectile +
// ejecta mass is exactly the initial mass.
//
// Each ejection is recorded (particle id, material, mass, launch time and step, launch position and
// velocity), for ejecta.csv (io/ejecta_csv.hpp).
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "craterkit/sph/particles/particles.hpp"

namespace craterkit::sph {

struct EjectaRecord {
  std::uint64_t id = 0;
  std::uint16_t material = 0;
  double mass = 0.0;                    // kg
  double time = 0.0;                    // s, launch (the end of the step in which it left)
  std::uint64_t step = 0;               // completed steps at launch
  double x = 0.0, y = 0.0, z = 0.0;     // m
  double vx = 0.0, vy = 0.0, vz = 0.0;  // m/s
};

struct EjectionRule {
  double radius = 0.0;        // R_ej, m; <= 0: no ejection at all
  double escape_speed = 0.0;  // m/s; <= 0: only the radius rule
};

// The record of particle i, launched now (its current position and velocity).
[[nodiscard]] EjectaRecord ejecta_record(const Particles& particles, std::size_t i, double time,
                                         std::uint64_t step);

// Flags every moving particle that the rule above ejects as particle_ejected and appends its record to
// `out` (in index order). neighbour_count[i]: interacting neighbours of particle i in its last rate
// evaluation (RateWorkspace::neighbour_count; a particle beyond its end counts as not clear). Returns the
// number flagged.
std::size_t eject_particles(Particles& particles, const EjectionRule& rule,
                            std::span<const std::uint32_t> neighbour_count, double time, std::uint64_t step,
                            std::vector<EjectaRecord>& out);

// Permutation (for Particles::permute) that moves every ejected particle behind the others, keeping the
// relative order within both groups; *active receives the number of particles not ejected.
std::vector<std::uint32_t> ejected_last_order(const Particles& particles, std::size_t* active);

}  // namespace craterkit::sph
