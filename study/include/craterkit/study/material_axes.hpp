#pragma once
// The material axes of a run (cohesion, friction, angle_of_repose, porosity, target.<key>) applied to a copy
// of its target material file, as docs/sweep.md states; the shipped file is never changed.
#include <string>
#include <vector>

#include "craterkit/study/study_file.hpp"
#include "craterkit/study/toml_document.hpp"

namespace craterkit::study {

// f = 2 sqrt(2) sin(theta) / (3 - sin(theta)) (Luther et al. 2022; docs/physics.md section 2), theta in
// degrees.
double friction_from_angle_of_repose(double degrees);
// The P-alpha initial distention of a porosity phi: alpha0 = 1 / (1 - phi).
double distention_from_porosity(double porosity);

// Applies the material axes among `values` to the material document (a target material file, schema in
// docs/materials.md): cohesion -> strength.cohesion, friction and angle_of_repose ->
// strength.friction_coefficient (strength.repose_angle_degrees removed), porosity ->
// porosity.initial_distention, target.<key> -> <key>. Returns whether anything changed. `origin` names the
// run's entry in messages ("study.toml: grid" gives "study.toml: grid.cohesion"): cohesion or friction
// without a Lundborg [strength] table, porosity without a P-alpha [porosity] table or with
// alpha0 <= porosity.transition_distention (the crush curve needs alpha0 > alpha_t) are InputErrors.
bool apply_material_axes(TomlDocument& material, const std::vector<AxisValue>& values,
                         const std::string& origin);

}  // namespace craterkit::study
