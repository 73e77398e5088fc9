#pragma once
// The contact law between two grains: Hertz normal force with viscoelastic damping set by a coefficient of
// restitution, Mindlin tangential force capped by sliding friction, rolling resistance
// (spring-dashpot-slider) capped by rolling friction, twisting resistance from the tangential law (Marshall
// 2009). docs/dem.md, "Contact law", gives each term, its LAMMPS keyword and where its value comes from.
#include <string>
#include <string_view>

namespace craterkit::dem {

struct GrainContact {
  double youngs_modulus =
      1.0e7;  // Pa; softened against the rock's (docs/dem.md: sets overlaps, not the flow)
  double poisson_ratio = 0.3;
  double restitution = 0.5;       // normal coefficient of restitution, (0, 1]
  double sliding_friction = 0.5;  // mu_s: |F_t| <= mu_s |F_n|
  double rolling_friction = 0.1;  // mu_r: |F_roll| <= mu_r |F_n| (torque R_eff |F_roll|)
};

// InputError naming `table`.key, the value and the range allowed, for the first value out of range.
void check_grain_contact(const GrainContact& contact, std::string_view table);

// The effective (reduced) modulus of two grains of the same material, E* = E / (2 (1 - nu^2)).
[[nodiscard]] double effective_modulus(const GrainContact& contact);

// Duration of a head-on Hertz collision of two equal grains (Johnson 1985, sec. 11.4):
// t_c = 2.868 (m*^2 / (R* E*^2 v))^(1/5) with m* = m/2, R* = d/4.
[[nodiscard]] double hertz_contact_time(const GrainContact& contact, double diameter, double grain_density,
                                        double impact_speed);

// The Young's modulus at which the contacts at the floor of a bed overlap by `overlap_fraction` of a grain
// diameter under the bed's weight: the vertical stress P = rho_b g H is carried by contact forces of mean
// f = pi d^2 P / (phi Z) (the stress-force relation of a random packing, Rothenburg & Bathurst 1989,
// Geotechnique 39, 601; phi = rho_b / rho_grain, coordination number Z = 5), and the Hertz overlap of equal
// grains is delta = (3 f / (4 E* sqrt(d/4)))^(2/3), solved for E. How soft grains may be (docs/dem.md).
[[nodiscard]] double youngs_modulus_for_overlap(double bulk_density, double grain_density, double gravity,
                                                double depth, double diameter, double poisson_ratio,
                                                double overlap_fraction);

// The pair and wall model of LAMMPS's `granular` styles for this contact (the arguments after
// `pair_coeff * *` or `fix wall/gran ... granular`), with the rolling spring set for grains of this diameter.
// The Young's modulus for which a grain hitting an equal grain at rest at `impact_speed` overlaps at most
// overlap_fraction of its diameter: the Hertz impact's largest overlap, delta = (15 m* v^2 / (16 E*
// sqrt(R*)))^(2/5) (Johnson 1985, sec. 11.4), solved for E* with m* = m/2, R* = d/4.
[[nodiscard]] double youngs_modulus_for_impact(double diameter, double grain_density, double impact_speed,
                                               double poisson_ratio, double overlap_fraction);

// The elastic energy of a Hertz contact of overlap delta between grains of reduced radius R*:
// (8/15) E* sqrt(R*) delta^(5/2), the work of F = (4/3) E* sqrt(R*) delta^(3/2).
[[nodiscard]] double hertz_elastic_energy(const GrainContact& contact, double reduced_radius, double overlap);

// The same contact without sliding and rolling friction: a wall standing for a mirror plane, along which
// grains slide and roll freely.
[[nodiscard]] GrainContact frictionless_wall(GrainContact contact);

[[nodiscard]] std::string lammps_contact_model(const GrainContact& contact, double diameter,
                                               double grain_density);

}  // namespace craterkit::dem
