#include "craterkit/dem/grain_contact.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "craterkit/common/checks.hpp"

namespace craterkit::dem {

namespace {

std::string key(std::string_view table, std::string_view name) {
  return fmt::format("{}.{}", table, name);
}

}  // namespace

void check_grain_contact(const GrainContact& contact, std::string_view table) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  require_positive(contact.youngs_modulus, key(table, "youngs_modulus"));
  require_in_range(contact.poisson_ratio, key(table, "poisson_ratio"), -1.0, 0.5, true, true);
  require_in_range(contact.restitution, key(table, "restitution"), 0.0, 1.0, true, false);
  require_in_range(contact.sliding_friction, key(table, "sliding_friction"), 0.0, inf);
  require_in_range(contact.rolling_friction, key(table, "rolling_friction"), 0.0, inf);
}

double effective_modulus(const GrainContact& contact) {
  return contact.youngs_modulus / (2.0 * (1.0 - contact.poisson_ratio * contact.poisson_ratio));
}

double hertz_contact_time(const GrainContact& contact, double diameter, double grain_density,
                          double impact_speed) {
  const double mass = grain_density * std::numbers::pi * diameter * diameter * diameter / 6.0;
  const double reduced_mass = 0.5 * mass;
  const double reduced_radius = 0.25 * diameter;
  const double modulus = effective_modulus(contact);
  return 2.868 *
         std::pow(reduced_mass * reduced_mass / (reduced_radius * modulus * modulus * impact_speed), 0.2);
}

double youngs_modulus_for_overlap(double bulk_density, double grain_density, double gravity, double depth,
                                  double diameter, double poisson_ratio, double overlap_fraction) {
  constexpr double coordination = 5.0;
  const double pressure = bulk_density * gravity * depth;
  const double packing_fraction = bulk_density / grain_density;
  const double force = std::numbers::pi * diameter * diameter * pressure / (packing_fraction * coordination);
  const double overlap = overlap_fraction * diameter;
  const double effective = 3.0 * force / (4.0 * std::sqrt(0.25 * diameter) * std::pow(overlap, 1.5));
  return 2.0 * (1.0 - poisson_ratio * poisson_ratio) * effective;
}

double youngs_modulus_for_impact(double diameter, double grain_density, double impact_speed,
                                 double poisson_ratio, double overlap_fraction) {
  const double mass = grain_density * std::numbers::pi * diameter * diameter * diameter / 6.0;
  const double overlap = overlap_fraction * diameter;
  const double reduced_modulus = 15.0 * 0.5 * mass * impact_speed * impact_speed /
                                 (16.0 * std::sqrt(0.25 * diameter) * std::pow(overlap, 2.5));
  return 2.0 * (1.0 - poisson_ratio * poisson_ratio) * reduced_modulus;
}

double hertz_elastic_energy(const GrainContact& contact, double reduced_radius, double overlap) {
  return 8.0 / 15.0 * effective_modulus(contact) * std::sqrt(reduced_radius) * std::pow(overlap, 2.5);
}

GrainContact frictionless_wall(GrainContact contact) {
  contact.sliding_friction = 0.0;
  contact.rolling_friction = 0.0;
  return contact;
}

std::string lammps_contact_model(const GrainContact& contact, double diameter, double grain_density) {
  // Rolling spring: the linear stiffness of the Hertz contact of two such grains under their own weight's
  // order of overlap, delta = 1e-3 d (k_n = 2 E* sqrt(R* delta), Johnson 1985 eq. 4.23 differentiated), times
  // 2.25 mu_r^2 (the rolling stiffness of the elastic-plastic spring-dashpot model in Ai et al. 2011,
  // Powder Technol. 206, 269, with the torque arm R* taken out, since LAMMPS applies it); its
  // dashpot damps the rolling spring critically. The slider (mu_r) sets the resistance a rolling contact
  // reaches, which is what the angle of repose feels (Zhou et al. 1999, Physica A 269, 536).
  const double reduced_radius = 0.25 * diameter;
  const double normal_stiffness =
      2.0 * effective_modulus(contact) * std::sqrt(reduced_radius * 1e-3 * diameter);
  const double rolling_stiffness =
      2.25 * contact.rolling_friction * contact.rolling_friction * normal_stiffness;
  const double reduced_mass = 0.5 * grain_density * std::numbers::pi * diameter * diameter * diameter / 6.0;
  const double rolling_damping = 2.0 * std::sqrt(rolling_stiffness * reduced_mass);
  // hertz/material E e nu with damping tsuji: the second number is read as the coefficient of restitution.
  // tangential mindlin NULL: k_t from E and nu; 1.0: tangential damping equal to the normal damping.
  return fmt::format(
      "hertz/material {:.17g} {:.17g} {:.17g} tangential mindlin NULL 1.0 {:.17g} rolling sds {:.17g} "
      "{:.17g} "
      "{:.17g} twisting marshall damping tsuji",
      contact.youngs_modulus, contact.restitution, contact.poisson_ratio, contact.sliding_friction,
      rolling_stiffness, rolling_damping, contact.rolling_friction);
}

}  // namespace craterkit::dem
