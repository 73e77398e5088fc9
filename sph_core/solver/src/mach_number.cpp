#include "craterkit/sph/solver/mach_number.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

#include "craterkit/sph/particles/particles.hpp"

namespace craterkit::sph {

MachNumber max_mach_number(std::span<const double> vx, std::span<const double> vy, std::span<const double> vz,
                           std::span<const double> sound_speed, std::span<const std::uint8_t> flags) {
  const std::size_t n = vx.size();
  if (vy.size() != n || vz.size() != n || sound_speed.size() != n || (!flags.empty() && flags.size() != n)) {
    throw std::invalid_argument(
        "max_mach_number: the velocity, sound-speed and flag arrays differ in length");
  }
  MachNumber best{};
  double best_squared = 0.0;  // compare M^2 = v^2/c^2: no square root per particle
#pragma omp parallel
  {
    double local_squared = 0.0;
    std::size_t local_particle = 0;
#pragma omp for nowait schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      if (!flags.empty() && (flags[i] & particle_ejected) != 0) continue;
      const double v2 = vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i];
      if (v2 == 0.0) continue;
      const double c2 = sound_speed[i] * sound_speed[i];
      const double m2 = c2 > 0.0 ? v2 / c2 : std::numeric_limits<double>::infinity();
      if (m2 > local_squared) {
        local_squared = m2;
        local_particle = i;
      }
    }
#pragma omp critical(craterkit_max_mach_number)
    {
      // Ties go to the lowest index, so the answer does not depend on the thread count.
      if (local_squared > best_squared ||
          (local_squared == best_squared && local_squared > 0.0 && local_particle < best.particle)) {
        best_squared = local_squared;
        best.particle = local_particle;
      }
    }
  }
  best.value = std::sqrt(best_squared);
  return best;
}

}  // namespace craterkit::sph
