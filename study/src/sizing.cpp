#include "craterkit/study/sizing.hpp"

#include <cmath>
#include <numbers>

#include "craterkit/common/input_error.hpp"

namespace craterkit::study {

double projectile_radius(double mass, double density) {
  constexpr double pi = std::numbers::pi;
  return std::cbrt(3.0 * mass / (4.0 * pi * density));
}

double projectile_mass(double radius, double density) {
  constexpr double pi = std::numbers::pi;
  return 4.0 / 3.0 * pi * radius * radius * radius * density;
}

Sizing size_run(const SizingRule& rule, const scaling::ScalingLaw& law, const SizingInput& input,
                std::optional<double> spacings) {
  Sizing s;
  s.projectile_radius = projectile_radius(input.projectile_mass, input.projectile_density);
  s.velocity = input.impact_angle == 0.0
                   ? input.impact_speed
                   : input.impact_speed * std::cos(input.impact_angle * std::numbers::pi / 180.0);
  const scaling::Impactor impactor{s.projectile_radius, input.projectile_density, s.velocity};
  const scaling::Target target{input.target_density, input.gravity, input.strength};
  try {
    s.predicted_crater_radius = scaling::crater_radius(law, impactor, target);
  } catch (const InputError&) {
    s.predicted_crater_radius = NAN;  // no finite crater (e.g. neither gravity nor strength): no prediction
  }
  s.spacings_across_radius = spacings.value_or(rule.spacings_across_radius);
  s.domain_radius = rule.domain_over_radius * s.predicted_crater_radius;
  s.particle_spacing = s.predicted_crater_radius / s.spacings_across_radius;
  s.inner_spacing = rule.core_spacing_over_projectile_radius * s.projectile_radius;
  s.end_time = rule.end_time_over_growth_time * std::sqrt(s.predicted_crater_radius / input.gravity);
  return s;
}

}  // namespace craterkit::study
