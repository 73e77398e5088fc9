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
[[nodiscard]] std::string lammps_contact_model(const GrainContact& contact, double diameter,
                                               double grain_density);

}  // namespace craterkit::dem
