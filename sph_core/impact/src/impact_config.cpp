#include "craterkit/impact/impact_config.hpp"

#include <cctype>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"

namespace craterkit::impact {

using namespace sph;

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// One shape primitive from a table holding `shape` and its keys (the other keys of `t` are the caller's).
ShapePart parse_part(TomlTable& t) {
  const std::string shape = t.text("shape", "", {"sphere", "cylinder", "half_space", "box"});
  if (shape.empty()) t.fail("shape", "missing: one of \"sphere\", \"cylinder\", \"half_space\", \"box\"");
  if (shape == "sphere") {
    Sphere s;
    const auto c = t.required_numbers("centre", 3);
    s.centre = {c[0], c[1], c[2]};
    const auto r = t.optional_number("radius", 0.0, inf, true);
    if (!r) t.fail("radius", "missing: the sphere radius in m (> 0)");
    s.radius = *r;
    return s;
  }
  if (shape == "cylinder") {
    VerticalCylinder c;
    const auto a = t.required_numbers("axis", 2);
    c.axis = {a[0], a[1]};
    const auto r = t.optional_number("radius", 0.0, inf, true);
    if (!r) t.fail("radius", "missing: the cylinder radius in m (> 0)");
    c.radius = *r;
    return c;
  }
  if (shape == "half_space") {
    HalfSpace h;
    const auto n = t.required_numbers("normal", 3);
    if (n[0] == 0.0 && n[1] == 0.0 && n[2] == 0.0) t.fail("normal", "must not be the zero vector");
    h.normal = {n[0], n[1], n[2]};
    const auto o = t.optional_number("offset", -inf, inf);
    if (!o) t.fail("offset", "missing: the points with normal . x < offset are inside (m)");
    h.offset = *o;
    return h;
  }
  AxisAlignedBox b;
  const auto lower = t.numbers("lower", 3, true);
  const auto upper = t.numbers("upper", 3, true);
  if (!lower && !upper) t.fail("lower", "missing: a box needs lower and/or upper corners (m)");
  if (lower) b.lower = {(*lower)[0], (*lower)[1], (*lower)[2]};
  if (upper) b.upper = {(*upper)[0], (*upper)[1], (*upper)[2]};
  for (int a = 0; a < 3; ++a) {
    if (!(b.lower[a] < b.upper[a]))
      t.fail("upper", "must exceed lower on every axis (axis " + std::to_string(a) + ")");
  }
  return b;
}

ImpactBoulder parse_boulder(TomlTable t, std::size_t index) {
  ImpactBoulder b;
  b.name = t.text("name", std::to_string(index + 1));
  for (char ch : b.name) {
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-')) {
      t.fail("name", "value \"" + b.name + "\" not allowed: letters, digits, '_' and '-' only");
    }
  }
  b.material = t.text("material", b.material);
  if (t.contains("parts")) {
    if (t.contains("shape")) t.fail("shape", "give either shape or parts, not both");
    std::vector<TomlTable> parts = t.tables("parts");
    if (parts.empty()) t.fail("parts", "expected a non-empty array of tables ([[...parts]])");
    for (auto& part : parts) {
      b.shape.parts.push_back(parse_part(part));
      part.finish();
    }
  } else {
    b.shape.parts.push_back(parse_part(t));
  }
  t.finish();
  return b;
}

}  // namespace

ImpactSetup parse_impact_setup(TomlTable t) {
  ImpactSetup s;
  s.target_material = t.text("target_material", s.target_material);
  s.projectile_material = t.text("projectile_material", s.projectile_material);
  s.projectile_mass = t.number("projectile_mass", s.projectile_mass, 0.0, inf, true);
  s.projectile_density = t.number("projectile_density", s.projectile_density, 0.0, inf, true);
  s.impact_speed = t.number("impact_speed", s.impact_speed, 0.0, inf, true);
  s.impact_angle = t.number("impact_angle", s.impact_angle, 0.0, 89.0);
  const std::string model = t.text("projectile_model", projectile_model_name(s.projectile_model),
                                   {"resolved", "point_source_stand_in"});
  s.projectile_model =
      model == "resolved" ? ProjectileModel::resolved : ProjectileModel::point_source_stand_in;
  s.stand_in_radius = t.number("stand_in_radius", s.stand_in_radius, 0.0, inf);
  if (s.stand_in_radius > 0.0 && s.projectile_model == ProjectileModel::resolved) {
    t.fail("stand_in_radius", "given but projectile_model = \"resolved\"");
  }
  s.coupling_exponent = t.number("coupling_exponent", s.coupling_exponent, 0.0, 1.0, true);
  s.domain_radius = t.number("domain_radius", s.domain_radius, 0.0, inf, true);
  s.particle_spacing = t.number("particle_spacing", s.particle_spacing, 0.0, s.domain_radius / 8.0, true);
  // Graded resolution (docs/impact_setup.md "Graded resolution"): particle_spacing is then the outer one.
  s.inner_spacing = t.number("inner_spacing", s.inner_spacing, 0.0, inf);
  if (s.inner_spacing > 0.0 && !(s.inner_spacing < s.particle_spacing)) {
    t.fail("inner_spacing", "value " + format_number(s.inner_spacing) + " out of range: allowed (0, " +
                                format_number(s.particle_spacing) +
                                ") below particle_spacing, the outer spacing (0: uniform lattice)");
  }
  const auto grading = t.optional_number("grading", 0.0, 0.2, true);
  const auto inner_radius = t.optional_number("inner_radius", 0.0, inf);
  if (s.inner_spacing == 0.0 && (grading || inner_radius)) {
    t.fail(grading ? "grading" : "inner_radius", "given but inner_spacing = 0 (uniform lattice)");
  }
  if (grading) s.grading = *grading;
  if (inner_radius) {
    s.inner_radius = *inner_radius;
    if (s.inner_radius > 0.0 && s.inner_radius < 4.0 * s.inner_spacing * (1.0 - 1e-12)) {
      t.fail("inner_radius", "value " + format_number(s.inner_radius) +
                                 " out of range: at least 4 inner_spacing = " +
                                 format_number(4.0 * s.inner_spacing) + " m (0: 8 inner_spacing)");
    }
  }
  // Far coarsening (docs/impact_setup.md "Graded resolution"): both keys or neither, graded targets only.
  const auto far_radius = t.optional_number("far_radius", 0.0, s.domain_radius, true);
  const auto far_spacing = t.optional_number("far_spacing", 0.0, s.domain_radius / 8.0, true);
  if (far_radius || far_spacing) {
    if (s.inner_spacing == 0.0) {
      t.fail(far_radius ? "far_radius" : "far_spacing", "given but inner_spacing = 0 (uniform lattice)");
    }
    if (!far_radius || !far_spacing) {
      t.fail(far_radius ? "far_spacing" : "far_radius",
             std::string("missing: far_radius and far_spacing go together (") +
                 (far_radius ? "far_radius" : "far_spacing") + " is given)");
    }
    s.far_radius = *far_radius;
    s.far_spacing = *far_spacing;
    if (!(s.far_spacing > s.particle_spacing)) {
      t.fail("far_spacing", "value " + format_number(s.far_spacing) +
                                " out of range: must be above particle_spacing (" +
                                format_number(s.particle_spacing) + " m), the spacing it grows from");
    }
  }
  s.fixed_shell_thickness =
      t.number("fixed_shell_thickness", s.fixed_shell_thickness, 0.0, s.domain_radius / 4.0);
  const std::string symmetry = t.text("symmetry", symmetry_name(s.symmetry), {"full", "quarter"});
  s.symmetry = symmetry == "quarter" ? DomainSymmetry::quarter : DomainSymmetry::full;
  s.transition_time = t.number("t_transition", s.transition_time, 0.0, inf);
  s.low_sound_speed_modulus = t.number("A_low", s.low_sound_speed_modulus, 0.0, inf, true);
  s.tensile_porosity = t.boolean("tensile_porosity", s.tensile_porosity);
  s.escape_speed = t.number("escape_speed", s.escape_speed, 0.0, inf);
  std::set<std::string> names;
  for (auto& table : t.tables("boulders")) {
    s.boulders.push_back(parse_boulder(table, s.boulders.size()));
    if (!names.insert(s.boulders.back().name).second) {
      throw InputError(t.source() + ": " + table.name() + ".name: \"" + s.boulders.back().name +
                       "\" used twice");
    }
  }
  if (s.symmetry == DomainSymmetry::quarter && s.impact_angle != 0.0) {
    t.fail("symmetry", "\"quarter\" needs a vertical impact (impact_angle = 0)");
  }
  if (s.symmetry == DomainSymmetry::quarter && !s.boulders.empty()) {
    t.fail("symmetry", "\"quarter\" cannot take boulders (the mirror planes would mirror them)");
  }
  t.finish();
  return s;
}

sph::SimulationConfig impact_simulation_defaults(const ImpactSetup& impact) {
  sph::SimulationConfig c;
  c.solver.smoothing.max_smoothing_ratio = 3.0;
  c.solver.viscosity.viscosity_switch = sph::ViscositySwitch::morris_monaghan;
  c.solver.viscosity.balsara = true;
  c.solver.time_step.energy_floor = impact.impact_speed * impact.impact_speed / 400.0;
  c.solver.time_step.velocity_change = 0.1;
  c.solver.time_step.block_levels = 8;
  return c;
}

ImpactConfig parse_impact_config(TomlTable& root) {
  (void)sph::read_problem_setup(root, {"impact"});
  ImpactConfig c;
  c.impact = parse_impact_setup(root.table("impact"));
  if (root.contains("late_stage")) {
    throw InputError(root.source() +
                     ": table [late_stage] given but problem.setup = \"impact\": use impact.t_transition "
                     "and impact.A_low");
  }
  {
    TomlTable s = root.table("crater");
    auto& k = c.crater;
    k.check_interval = s.number("check_interval", k.check_interval, 0.0, inf);
    k.radius_tolerance = s.number("radius_tolerance", k.radius_tolerance, 0.0, 1.0, true);
    k.kinetic_energy_fraction =
        s.number("kinetic_energy_fraction", k.kinetic_energy_fraction, 0.0, 1.0, true);
    k.window_fraction = s.number("window_fraction", k.window_fraction, 0.0, 1.0, true);
    k.stop_when_grown = s.boolean("stop_when_grown", k.stop_when_grown);
    s.finish();
  }
  c.simulation = sph::parse_simulation_config(root, impact_simulation_defaults(c.impact));
  root.finish();
  return c;
}

ImpactConfig parse_impact_config(const std::string& toml_text, const std::string& source) {
  TomlTable root = TomlTable::parse(toml_text, source);
  return parse_impact_config(root);
}

ImpactConfig load_impact_config(const std::filesystem::path& path) {
  TomlTable root = TomlTable::parse_file(path);
  return parse_impact_config(root);
}

}  // namespace craterkit::impact
