#include "craterkit/impact/impact_config.hpp"

#include <cctype>
#include <cmath>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include "craterkit/common/input_error.hpp"
#include "toml_keys.hpp"

namespace craterkit::sph {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

// One shape primitive from a table holding `shape` and its keys (the other keys of `t` are the caller's).
ShapePart parse_part(TomlKeys& t) {
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

ImpactBoulder parse_boulder(const toml::table& table, std::size_t index, const std::string& source) {
  const std::string name = "impact.boulders[" + std::to_string(index) + "]";
  TomlKeys t(&table, name, source);
  ImpactBoulder b;
  b.name = t.text("name", std::to_string(index + 1));
  for (char ch : b.name) {
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-')) {
      t.fail("name", "value \"" + b.name + "\" not allowed: letters, digits, '_' and '-' only");
    }
  }
  b.material = t.text("material", b.material);
  const toml::node* parts = t.find("parts");
  if (parts != nullptr) {
    if (table.get("shape") != nullptr) t.fail("shape", "give either shape or parts, not both");
    const toml::array* array = parts->as_array();
    if (array == nullptr || array->empty())
      t.fail("parts", "expected a non-empty array of tables ([[...parts]])");
    for (std::size_t j = 0; j < array->size(); ++j) {
      const toml::table* part = array->get(j)->as_table();
      if (part == nullptr) t.fail("parts", "element " + std::to_string(j) + " is not a table");
      TomlKeys pt(part, name + ".parts[" + std::to_string(j) + "]", source);
      b.shape.parts.push_back(parse_part(pt));
      pt.finish();
    }
  } else {
    b.shape.parts.push_back(parse_part(t));
  }
  t.finish();
  return b;
}

}  // namespace

ImpactSetup parse_impact_setup(const toml::table& impact, const std::string& source) {
  TomlKeys t(&impact, "impact", source);
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
  s.fixed_shell_thickness =
      t.number("fixed_shell_thickness", s.fixed_shell_thickness, 0.0, s.domain_radius / 4.0);
  const std::string symmetry = t.text("symmetry", symmetry_name(s.symmetry), {"full", "quarter"});
  s.symmetry = symmetry == "quarter" ? DomainSymmetry::quarter : DomainSymmetry::full;
  s.transition_time = t.number("t_transition", s.transition_time, 0.0, inf);
  s.low_sound_speed_modulus = t.number("A_low", s.low_sound_speed_modulus, 0.0, inf, true);
  s.escape_speed = t.number("escape_speed", s.escape_speed, 0.0, inf);
  if (const toml::node* boulders = t.find("boulders")) {
    const toml::array* array = boulders->as_array();
    if (array == nullptr) t.fail("boulders", "expected an array of tables ([[impact.boulders]])");
    std::set<std::string> names;
    for (std::size_t i = 0; i < array->size(); ++i) {
      const toml::table* table = array->get(i)->as_table();
      if (table == nullptr) t.fail("boulders", "element " + std::to_string(i) + " is not a table");
      s.boulders.push_back(parse_boulder(*table, i, source));
      if (!names.insert(s.boulders.back().name).second) {
        throw InputError(source + ": impact.boulders[" + std::to_string(i) + "].name: \"" +
                         s.boulders.back().name + "\" used twice");
      }
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

}  // namespace craterkit::sph
