#include "craterkit/dem/grains.hpp"

#include <numbers>

namespace craterkit::dem {

void Grains::add(double px, double py, double pz, double grain_diameter, double grain_density) {
  x.push_back(px);
  y.push_back(py);
  z.push_back(pz);
  for (auto* v : {&vx, &vy, &vz, &omega_x, &omega_y, &omega_z}) v->push_back(0.0);
  diameter.push_back(grain_diameter);
  density.push_back(grain_density);
}

double Grains::volume(std::size_t i) const {
  return std::numbers::pi * diameter[i] * diameter[i] * diameter[i] / 6.0;
}

double Grains::mass(std::size_t i) const {
  return density[i] * volume(i);
}

double total_mass(const Grains& grains) {
  double sum = 0;
  for (std::size_t i = 0; i < grains.size(); ++i) sum += grains.mass(i);
  return sum;
}

std::array<double, 3> total_momentum(const Grains& grains) {
  std::array<double, 3> p{0, 0, 0};
  for (std::size_t i = 0; i < grains.size(); ++i) {
    const double m = grains.mass(i);
    p[0] += m * grains.vx[i];
    p[1] += m * grains.vy[i];
    p[2] += m * grains.vz[i];
  }
  return p;
}

double kinetic_energy(const Grains& grains) {
  double sum = 0;
  for (std::size_t i = 0; i < grains.size(); ++i) {
    const double m = grains.mass(i);
    const double inertia = 0.1 * m * grains.diameter[i] * grains.diameter[i];  // 2/5 m r^2
    const double v2 = grains.vx[i] * grains.vx[i] + grains.vy[i] * grains.vy[i] + grains.vz[i] * grains.vz[i];
    const double w2 = grains.omega_x[i] * grains.omega_x[i] + grains.omega_y[i] * grains.omega_y[i] +
                      grains.omega_z[i] * grains.omega_z[i];
    sum += 0.5 * (m * v2 + inertia * w2);
  }
  return sum;
}

}  // namespace craterkit::dem
