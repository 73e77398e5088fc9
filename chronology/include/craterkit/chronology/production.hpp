#pragma once
// Crater production (docs/physics.md sec. 7): the number of craters with rim-to-rim diameter larger than D
// formed per unit area per year,
//   r(D) = < P_i X(a) N(>a(D; U)) / A_surface >_U,
//   a(D; U)  impactor radius that makes an apparent crater radius R = D / (2 rim_to_apparent) at speed U
//            (the inverse scaling law, see scaled_production.hpp),
//   X(a)     impact cross-section (R_t + a)^2 or R_t^2 (conventions.hpp, CrossSection),
//   P_i      intrinsic collision probability (m^-2 yr^-1 here; bodies store km^-2 yr^-1),
//   N(>a)    impactor population (population.hpp),
//   < >_U    average over the impact-speed distribution (a single speed, or a table of weights).
// Because a(D) increases with D, every impactor larger than a(D) makes a crater larger than D.
#include <functional>
#include <vector>

#include "craterkit/chronology/body.hpp"
#include "craterkit/chronology/conventions.hpp"
#include "craterkit/chronology/population.hpp"

namespace craterkit::chronology {

// Inverse scaling law: impactor radius (m) for an apparent crater radius (m) at impact speed (m/s).
using ImpactorRadiusFunction = std::function<double(double apparent_crater_radius, double impact_speed)>;

// Discrete impact-speed distribution: speeds (m/s) with weights (normalised when used). A single speed
// is one entry of weight 1.
struct SpeedDistribution {
  std::vector<double> speed;
  std::vector<double> weight;
};
SpeedDistribution single_speed(double speed);
void validate(const SpeedDistribution& speeds);
// CSV with columns speed_m_s (or speed_km_s) and weight; errors name file:line.
SpeedDistribution read_speed_distribution(const std::string& path);

struct ProductionSetup {
  ImpactorPopulation population;
  double intrinsic_probability = 0.0;  // P_i, m^-2 yr^-1
  double target_radius = 0.0;          // R_t, m
  double surface_area = 0.0;           // m^2 (the body's, over which impacts spread)
  SpeedDistribution speeds;
  DiameterConvention diameter;
  CrossSection cross_section = CrossSection::target_plus_impactor;
};

// The setup for a body: P_i, impact speed (unless `speeds` is given) and region from the body's
// collision environment, its mean radius and surface area.
ProductionSetup production_setup_for_body(const Body& body, CollisionRegion region,
                                          ImpactorPopulation population,
                                          const SpeedDistribution* speeds = nullptr);

// Weighted mean speed of a distribution (m/s).
double mean_speed(const SpeedDistribution& speeds);

// P_i in km^-2 yr^-1 -> m^-2 yr^-1.
inline double per_square_metre(double per_square_km) {
  return per_square_km * 1e-6;
}

// Impacts per year on the body by impactors larger than a (at one speed, so no average here).
double impact_rate(const ProductionSetup& setup, double impactor_radius);

// r(D): craters with rim diameter > D per m^2 per year.
double crater_production_rate(const ProductionSetup& setup, const ImpactorRadiusFunction& impactor_radius,
                              double rim_diameter);

// -dr/dD (per m^2 per year per m of diameter), from the population's differential number and the
// slope da/dD of the inverse law (central difference in log D with relative step `step`).
double differential_production_rate(const ProductionSetup& setup,
                                    const ImpactorRadiusFunction& impactor_radius, double rim_diameter,
                                    double step = 1e-4);

// A production function D -> r(D) bound to a setup and a scaling law (for model ages).
using ProductionFunction = std::function<double(double rim_diameter)>;
ProductionFunction production_function(ProductionSetup setup, ImpactorRadiusFunction impactor_radius);

}  // namespace craterkit::chronology
