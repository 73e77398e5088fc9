#pragma once
// Conserved quantities of the particle set (mass, momentum, kinetic, internal and potential energy).
//
// Sums run over ALL particles, fixed (boundary) and ejected ones included: ejected particles still
// carry mass, momentum and energy, so removing them from the hydrodynamics must not show up as a
// loss. Fixed particles contribute their mass, their (normally zero) velocity and their internal and
// potential energy; momentum is not conserved in runs with fixed walls, which absorb it. With mirror
// planes (a quarter-domain impact) the sums are those of the simulated quarter: energy is conserved,
// momentum normal to a plane is not (the plane pushes back).
// Sums are taken in fixed blocks combined in a fixed order with compensated (Neumaier) summation, so
// the result does not depend on the number of OpenMP threads.
#include <array>
#include <cstdint>

#include "craterkit/sph/particles/particles.hpp"

namespace craterkit::sph {

struct ConservedQuantities {
  double time = 0;                                        // s
  std::uint64_t step = 0;                                 // completed time steps
  double mass = 0;                                        // kg
  double momentum_x = 0, momentum_y = 0, momentum_z = 0;  // kg m/s
  double kinetic_energy = 0;                              // J, sum m |v|^2 / 2
  double internal_energy = 0;                             // J, sum m u
  double potential_energy = 0;                            // J, -sum m g.x (zero at the origin of coordinates)
  double total_energy = 0;                                // J, kinetic + internal + potential
  double absolute_momentum = 0;  // kg m/s, sum m |v|: the scale for relative momentum errors
};

// gravity: the constant acceleration vector, m/s^2 (e.g. {0, 0, -1.5e-4}).
// time and step are left zero: the caller sets them.
ConservedQuantities measure_conserved(const Particles& particles, std::array<double, 3> gravity);

// |E - E0| / |E0|; if E0 == 0, |E - E0| / (|K0| + |U0| + |P0|) with the initial kinetic, internal
// and potential energies; if those vanish too, the absolute change |E - E0| in J.
double relative_energy_error(const ConservedQuantities& initial, const ConservedQuantities& now);

// |p - p0| / max(absolute_momentum0, absolute_momentum) (0 if both vanish): the change of total
// momentum relative to the momentum carried by the particles.
double relative_momentum_error(const ConservedQuantities& initial, const ConservedQuantities& now);

}  // namespace craterkit::sph
