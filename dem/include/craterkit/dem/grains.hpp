#pragma once
// A set of spherical grains as structure of arrays: position, velocity, angular velocity, diameter and the
// density of the grain material. Grain i's mass is density pi d^3 / 6 and its moment of inertia m d^2 / 10.
#include <array>
#include <cstddef>
#include <vector>

namespace craterkit::dem {

struct Grains {
  std::vector<double> x, y, z;
  std::vector<double> vx, vy, vz;
  std::vector<double> omega_x, omega_y, omega_z;  // rad/s
  std::vector<double> diameter;
  std::vector<double> density;  // kg/m^3 of the grain material

  [[nodiscard]] std::size_t size() const { return x.size(); }
  void add(double px, double py, double pz, double grain_diameter, double grain_density);
  [[nodiscard]] double mass(std::size_t i) const;
  [[nodiscard]] double volume(std::size_t i) const;
};

[[nodiscard]] double total_mass(const Grains& grains);
[[nodiscard]] std::array<double, 3> total_momentum(const Grains& grains);
// Translational plus rotational kinetic energy.
[[nodiscard]] double kinetic_energy(const Grains& grains);

}  // namespace craterkit::dem
