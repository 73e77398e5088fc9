#pragma once
// The local particle spacing of a graded-resolution impact target (docs/physics.md section 4;
// graded_target.hpp, docs/impact_setup.md "Graded resolution"), as a function of the distance r from the
// impact point.
//
// The target has a uniform core of spacing dx0 for r < R_c and, outside it, hemispherical shells whose
// thickness grows by the factor (1 + s) from one shell to the next, dx_{k+1} = min(dx_max, dx_k (1 + s)),
// with centres r_{k+1} = r_k + (dx_k + dx_{k+1})/2. Per shell the spacing grows by s dx_k over the distance
// (1 + s/2) dx_k, so through the shell centres the spacing is exactly linear in r:
//     dx(r) = dx0 + s/(1 + s/2) (r - r_0),   r_0 = R_c + dx0/2 (the first shell's centre),
// capped at dx_max. Far from the crater (optional, far_radius > 0): from the first shell that starts at or
// beyond r_f = far_radius the shells grow again by (1 + s) per shell, up to dx_far = far_spacing, so that
//     dx(r) = min(dx_far, dx_max + s/(1 + s/2) (r - r_f))   for r > r_f
// to within one shell (the set-up spreads the rounding of the shells to R_dom over all of them). This header
// holds that law alone, so that the crater measurement can use it without the set-up: the measurement's
// steps and tolerances follow the local spacing (crater_measurement.hpp).
#include <algorithm>

namespace craterkit::impact {

struct GradedSpacing {
  double inner_spacing = 0.0;  // dx0, m (the core); 0 or >= outer_spacing: uniform at outer_spacing
  double inner_radius = 0.0;   // R_c, m: radius of the uniform core
  double grading = 0.0;        // s, relative growth of the spacing per spacing outward; 0: uniform
  double outer_spacing = 0.0;  // dx_max, m (the impact set-up's particle_spacing)
  double far_radius = 0.0;     // r_f, m: where the spacing grows again (0: dx_max out to R_dom)
  double far_spacing = 0.0;    // dx_far, m (> dx_max): the spacing it grows to beyond r_f

  [[nodiscard]] bool graded() const noexcept {
    return inner_spacing > 0.0 && inner_spacing < outer_spacing && grading > 0.0;
  }
  // The far coarsening is on (and needs a graded target).
  [[nodiscard]] bool coarsened() const noexcept {
    return graded() && far_radius > 0.0 && far_spacing > outer_spacing;
  }
  // d(dx)/dr through the shell centres: s / (1 + s/2).
  [[nodiscard]] double slope() const noexcept { return grading / (1.0 + 0.5 * grading); }
  // dx(r), m; outer_spacing everywhere when not graded.
  [[nodiscard]] double at(double r) const noexcept {
    if (!graded()) return outer_spacing;
    const double r0 = inner_radius + 0.5 * inner_spacing;
    if (r <= r0) return inner_spacing;
    if (coarsened() && r > far_radius)
      return std::min(far_spacing, outer_spacing + slope() * (r - far_radius));
    return std::min(outer_spacing, inner_spacing + slope() * (r - r0));
  }
  // The distance at which the spacing reaches dx_max (the end of the graded zone).
  [[nodiscard]] double outer_radius() const noexcept {
    if (!graded()) return 0.0;
    return inner_radius + 0.5 * inner_spacing + (outer_spacing - inner_spacing) / slope();
  }
};

}  // namespace craterkit::impact
