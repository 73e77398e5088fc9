#include "craterkit/dem_late_stage/grain_crater.hpp"

#include <fmt/format.h>

#include <cmath>

#include "craterkit/common/input_error.hpp"
#include "craterkit/dem_late_stage/handoff.hpp"

namespace craterkit::dem_late_stage {

sph::Particles grains_as_particles(const dem::Grains& grains, const std::vector<int>& roles,
                                   const GrainMeasurement& measurement) {
  sph::Particles particles;
  particles.resize(grains.size());
  for (std::size_t g = 0; g < grains.size(); ++g) {
    const double m = grains.mass(g);
    particles.id[g] = g + 1;
    particles.x[g] = grains.x[g];
    particles.y[g] = grains.y[g];
    particles.z[g] = grains.z[g] - measurement.plane_height;
    particles.vx[g] = grains.vx[g];
    particles.vy[g] = grains.vy[g];
    particles.vz[g] = grains.vz[g];
    particles.mass[g] = m;
    particles.density[g] = measurement.bulk_density;
    particles.smoothing_length[g] = measurement.eta * std::cbrt(m / measurement.bulk_density);
    const int role = roles.empty() ? static_cast<int>(GrainRole::moving) : roles[g];
    if (role == static_cast<int>(GrainRole::flying)) particles.flags[g] = sph::particle_ejected;
    if (role == static_cast<int>(GrainRole::frozen)) particles.flags[g] = sph::particle_fixed;
  }
  return particles;
}

double grain_surface_height(const dem::Grains& grains, const std::vector<int>& roles, double bulk_density,
                            double eta, const std::vector<std::array<double, 2>>& columns) {
  const sph::Particles particles = grains_as_particles(grains, roles, {bulk_density, eta, 0.0});
  double step = 0.0;
  for (std::size_t g = 0; g < particles.size(); ++g) step = std::max(step, particles.smoothing_length[g]);
  const auto samples = impact::sample_columns(particles, sph::KernelType::cubic_spline, 0.5 * bulk_density,
                                              0.05 * step, columns);
  double sum = 0.0;
  std::size_t found = 0;
  for (const auto& s : samples) {
    if (!std::isfinite(s.surface_height)) continue;
    sum += s.surface_height;
    ++found;
  }
  if (found == 0)
    throw InputError(fmt::format("grain surface: none of the {} columns reaches the grains", columns.size()));
  return sum / static_cast<double>(found);
}

}  // namespace craterkit::dem_late_stage
