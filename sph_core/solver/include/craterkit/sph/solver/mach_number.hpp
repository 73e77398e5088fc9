#pragma once
// The largest Mach number |v|/c of the moving particles: the low-sound-speed medium of the late stage
// (docs/physics.md section 3) must stay nearly incompressible for the flow it carries, so the solver logs it
// at the switch and tracks it over the late stage.
#include <cstddef>
#include <cstdint>
#include <span>

namespace craterkit::sph {

// The largest Mach number |v|/c over the particles, and where.
// Particles flagged particle_ejected are skipped (they are out of the hydrodynamics); flags may be empty
// (all particles count). A moving particle with c = 0 has an infinite Mach number. Zero particles: 0.
struct MachNumber {
  double value = 0.0;
  std::size_t particle = 0;  // index of the particle where it is reached
};
MachNumber max_mach_number(std::span<const double> vx, std::span<const double> vy, std::span<const double> vz,
                           std::span<const double> sound_speed, std::span<const std::uint8_t> flags = {});

}  // namespace craterkit::sph
