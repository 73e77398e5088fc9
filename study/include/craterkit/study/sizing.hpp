#pragma once
// The sizing rule of a study (study_file.hpp SizingRule, docs/sweep.md "Sizing"): the crater radius the
// study's scaling law predicts for a run sets its domain, spacings and end time, so that runs of very
// different projectiles have the same number of spacings across their crater.
#include "craterkit/scaling/point_source.hpp"
#include "craterkit/study/study_file.hpp"

namespace craterkit::study {

// What the prediction needs of a run.
struct SizingInput {
  double projectile_mass = 0.0;     // m, kg
  double projectile_density = 0.0;  // delta, kg/m^3
  double impact_speed = 0.0;        // U, m/s
  double impact_angle = 0.0;        // degrees from the vertical (the law takes the normal component U cos)
  double target_density = 0.0;      // bulk: the material's reference density / alpha0, kg/m^3
  double gravity = 0.0;             // |g|, m/s^2
  double strength = 0.0;            // Y = the target's cohesion, Pa
};

struct Sizing {
  double projectile_radius = 0.0;        // a = (3 m / (4 pi delta))^(1/3), m
  double velocity = 0.0;                 // U cos(theta), m/s
  double predicted_crater_radius = 0.0;  // R_pred, m (NaN when the law gives no finite crater)
  double spacings_across_radius = 0.0;   // n
  double domain_radius = 0.0;            // m
  double particle_spacing = 0.0;         // dx_max, m
  double inner_spacing = 0.0;            // dx0, m
  double end_time = 0.0;                 // s
};

// a as the impact set-up computes it (impact_setup.cpp), so that the tables agree with the run record.
double projectile_radius(double mass, double density);
// The mass of a projectile of radius a: 4/3 pi a^3 delta.
double projectile_mass(double radius, double density);

// The prediction and the sizes of the rule, with n = `spacings` (the resolution axis) or the rule's own. The
// sizes are filled even when rule.enabled is false (they are then not applied by the planner).
Sizing size_run(const SizingRule& rule, const scaling::ScalingLaw& law, const SizingInput& input,
                std::optional<double> spacings = std::nullopt);

}  // namespace craterkit::study
