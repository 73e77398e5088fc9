#include "craterkit/impact/impact_setup.hpp"
#include "craterkit/sph/io/material_file.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include "craterkit/common/checks.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/impact/graded_target.hpp"
#include "craterkit/impact/lithostatic.hpp"
#include "craterkit/sph/physics/material_response.hpp"

namespace craterkit::impact {

using namespace sph;

namespace {

// The smallest sphere radius, in lattice spacings, accepted for the particle projectile: a sphere of
// radius 2 dx on the offset lattice holds 32 particles (two layers through its centre), the least that
// still carries a shape and a centre of mass on the axis.
constexpr double min_projectile_radius_in_spacings = 2.0;

std::string number_text(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

[[noreturn]] void fail(const std::string& key, const std::string& what) {
  throw InputError("impact." + key + ": " + what);
}

double reference_density(const Material& material, const std::string& key) {
  const auto reference = solid_reference(material.eos);
  if (!reference) {
    fail(key,
         "material \"" + material.name + "\" has no solid reference density (an ideal gas is not allowed)");
  }
  return reference->density;
}

// The graded keys (docs/impact_setup.md "Graded resolution"); nothing to check for the uniform lattice.
void validate_grading(const ImpactSetup& s) {
  if (!(s.inner_spacing >= 0.0) || !std::isfinite(s.inner_spacing)) {
    fail("inner_spacing", "value " + number_text(s.inner_spacing) +
                              " out of range: must be >= 0 (0: uniform lattice at particle_spacing)");
  }
  if (!(s.inner_spacing > 0.0)) return;
  if (!(s.inner_spacing < s.particle_spacing)) {
    fail("inner_spacing", "value " + number_text(s.inner_spacing) + " out of range: allowed (0, " +
                              number_text(s.particle_spacing) +
                              ") below particle_spacing, the outer spacing (0: uniform lattice)");
  }
  require_in_range(s.grading, "impact.grading", 0.0, 0.2, true);
  if (!(s.inner_radius >= 0.0) || !std::isfinite(s.inner_radius)) {
    fail("inner_radius", "value " + number_text(s.inner_radius) + " out of range: must be >= 0 (0: 8 dx0)");
  }
  if (s.inner_radius > 0.0 && s.inner_radius < 4.0 * s.inner_spacing * (1.0 - 1e-12)) {
    fail("inner_radius", "value " + number_text(s.inner_radius) +
                             " out of range: at least 4 inner_spacing = " +
                             number_text(4.0 * s.inner_spacing) + " m (0: 8 inner_spacing)");
  }
  if (s.far_radius == 0.0 && s.far_spacing == 0.0) return;
  if (!(s.far_radius > 0.0 && s.far_radius < s.domain_radius)) {
    fail("far_radius", "value " + number_text(s.far_radius) + " out of range: allowed (0, " +
                           number_text(s.domain_radius) + ") inside the domain, with far_spacing");
  }
  if (!(s.far_spacing > s.particle_spacing) || !std::isfinite(s.far_spacing)) {
    fail("far_spacing", "value " + number_text(s.far_spacing) +
                            " out of range: must be above particle_spacing (" +
                            number_text(s.particle_spacing) + " m), the spacing it grows from");
  }
}

bool is_graded(const ImpactSetup& s) {
  return s.inner_spacing > 0.0;
}

// The spacing of the projectile's lattice: the core's on a graded target.
double projectile_spacing(const ImpactSetup& s) {
  return is_graded(s) ? s.inner_spacing : s.particle_spacing;
}

double core_radius_of(const ImpactSetup& s) {
  return s.inner_radius > 0.0 ? s.inner_radius : 8.0 * s.inner_spacing;
}

// The local spacing law of a graded target (graded_spacing.hpp), with the far coarsening if asked for.
GradedSpacing graded_spacing_of(const ImpactSetup& s) {
  return {s.inner_spacing, core_radius_of(s), s.grading, s.particle_spacing, s.far_radius, s.far_spacing};
}

std::size_t add_particle(Particles& p, double x, double y, double z) {
  const std::size_t i = p.size();
  p.resize(i + 1);
  p.id[i] = i;
  p.x[i] = x;
  p.y[i] = y;
  p.z[i] = z;
  return i;
}

// Sets density, distention, E = 0, pressure and sound speed of particle i from its material.
void set_state(Particles& p, std::size_t i, const Material& material, double density, double distention) {
  p.density[i] = density;
  p.distention[i] = distention;
  p.specific_energy[i] = 0.0;
  const MaterialState s = evaluate_material(material, density, 0.0, distention, 0.0);
  p.pressure[i] = s.pressure;
  p.sound_speed[i] = s.sound_speed;
}

// The material id at a point: boulder b (id 2 + b, the first that contains it) wherever a boulder is, else
// the target (0) below the surface z = 0, else -1 (empty space above the surface).
int material_at(const ImpactSetup& s, double x, double y, double z) {
  for (std::size_t b = 0; b < s.boulders.size(); ++b) {
    if (contains(s.boulders[b].shape, x, y, z)) return static_cast<int>(2 + b);
  }
  return z < 0.0 ? 0 : -1;
}

// The uniform lattice target (docs/impact_setup.md "Geometry").
void build_lattice_target(const ImpactSetup& s, double alpha, double g, double shell, ProblemSetup& problem,
                          ImpactSummary& summary) {
  // Target and boulders, column by column (x, y), each column from the top down so that the
  // lithostatic pressure is integrated through the material actually above each node.
  Particles& p = problem.particles;
  const double dx = s.particle_spacing, R = s.domain_radius, h = summary.smoothing_length;
  const auto n = static_cast<long>(std::ceil(R / dx)) + 1;
  const long first = s.symmetry == DomainSymmetry::quarter ? 0 : -n;
  const double volume = dx * dx * dx;
  const double R2 = R * R;
  const double inner2 = (R - shell) * (R - shell);
  for (long i = first; i < n; ++i) {
    const double x = (static_cast<double>(i) + 0.5) * dx;
    for (long j = first; j < n; ++j) {
      const double y = (static_cast<double>(j) + 0.5) * dx;
      if (x * x + y * y >= R2) continue;
      double pressure = 0.0;  // at the top of the current node's cell
      for (long k = -n; k < n; ++k) {
        const double z = -(static_cast<double>(k) + 0.5) * dx;
        const double r2 = x * x + y * y + z * z;
        if (r2 >= R2) continue;
        const int material = material_at(s, x, y, z);
        if (material < 0) continue;  // empty space above the surface: the pressure is unchanged
        const Material& m = problem.materials[static_cast<std::size_t>(material)];
        const double centre_pressure = lithostatic_pressure_after(m, pressure, 0.5 * dx, g);
        pressure = lithostatic_pressure_after(m, centre_pressure, 0.5 * dx, g);
        const LithostaticState state = lithostatic_state(m, centre_pressure);
        const std::size_t id = add_particle(p, x, y, z);
        p.material[id] = static_cast<std::uint16_t>(material);
        p.mass[id] = state.density * volume;
        p.smoothing_length[id] = h;
        p.viscosity_alpha[id] = alpha;
        set_state(p, id, m, state.density, state.distention);
        if (r2 > inner2) {
          p.flags[id] |= particle_fixed;
          ++summary.fixed_particles;
        }
        if (material == 0) {
          ++summary.target_particles;
        } else {
          ++summary.boulder_particles[static_cast<std::size_t>(material - 2)];
        }
        summary.max_lithostatic_pressure = std::max(summary.max_lithostatic_pressure, p.pressure[id]);
      }
    }
  }
}

// The graded target (graded_target.hpp; docs/impact_setup.md "Graded resolution"): the graded points below
// z = 0 are target or boulder, their mirror images above z = 0 exist only inside boulders; each particle
// stands for its cell V (mass rho V, h = eta V^(1/3)). Lithostatic state per particle, down its own column.
void build_graded_target(const ImpactSetup& s, double eta, double alpha, double g, double shell,
                         ProblemSetup& problem, ImpactSummary& summary) {
  const double R = s.domain_radius;
  const GradedSpacing spacing = graded_spacing_of(s);
  if (spacing.inner_radius > 0.5 * R) {
    fail("inner_radius", "value " + number_text(spacing.inner_radius) +
                             " out of range: at most R_dom / 2 = " + number_text(0.5 * R) + " m");
  }
  // The core alone (counted node by node in graded_layout) must not be absurdly large.
  const double core_estimate =
      2.0 / 3.0 * std::numbers::pi * std::pow(spacing.inner_radius / s.inner_spacing, 3);
  if (core_estimate > 4e8) {
    fail("inner_radius", "value " + number_text(spacing.inner_radius) + " would give about " +
                             number_text(core_estimate) + " core particles at inner_spacing " +
                             number_text(s.inner_spacing) + " m (at most 4e8)");
  }
  if (spacing.coarsened() && !(spacing.far_radius >= spacing.outer_radius())) {
    fail("far_radius", "value " + number_text(spacing.far_radius) + " out of range: at least " +
                           number_text(spacing.outer_radius()) +
                           " m, where the shells reach particle_spacing (the end of the graded zone)");
  }
  GradedLayout layout;
  try {
    layout = graded_layout(spacing, R);
  } catch (const std::invalid_argument& e) {
    fail("inner_radius",
         "value " + number_text(spacing.inner_radius) + " does not fit the domain: " + e.what());
  }
  const double estimate =
      static_cast<double>(graded_point_count(layout)) / (s.symmetry == DomainSymmetry::quarter ? 4.0 : 1.0);
  if (estimate > 4e8) {
    fail("inner_spacing", "value " + number_text(s.inner_spacing) + " would give " + number_text(estimate) +
                              " target particles (at most 4e8)");
  }
  summary.graded = true;
  summary.inner_spacing = spacing.inner_spacing;
  summary.grading = spacing.grading;
  summary.inner_radius = spacing.inner_radius;
  summary.core_radius = layout.core_radius;
  summary.shells = layout.shells.size();
  summary.graded_shells = layout.graded_shells;
  summary.graded_radius =
      layout.graded_shells < layout.shells.size() ? layout.shells[layout.graded_shells].inner : R;
  if (spacing.coarsened()) {
    summary.far_radius = spacing.far_radius;
    summary.far_spacing = spacing.far_spacing;
    summary.coarse_shells = layout.coarse_shells;
    summary.far_shells_radius =
        layout.coarse_shells > 0 ? layout.shells[layout.shells.size() - layout.coarse_shells].inner : R;
  }
  summary.min_smoothing_length = std::numeric_limits<double>::infinity();
  summary.max_smoothing_length = 0.0;

  // Points and materials: the four mirror images of each quadrant point (one with quarter symmetry),
  // below z = 0 and, inside boulders, above.
  const std::vector<GradedPoint> quadrant = graded_quadrant_points(layout, eta);
  Particles& p = problem.particles;
  std::vector<double> volume;
  std::vector<bool> core;
  const int images = s.symmetry == DomainSymmetry::quarter ? 1 : 4;
  const double sx[4] = {1.0, -1.0, 1.0, -1.0}, sy[4] = {1.0, 1.0, -1.0, -1.0};
  for (const GradedPoint& q : quadrant) {
    for (int m = 0; m < images; ++m) {
      for (const double sz : {1.0, -1.0}) {
        if (sz < 0.0 && s.boulders.empty()) continue;
        const double x = sx[m] * q.x, y = sy[m] * q.y, z = sz * q.z;
        const int material = material_at(s, x, y, z);
        if (material < 0) continue;
        const std::size_t id = add_particle(p, x, y, z);
        p.material[id] = static_cast<std::uint16_t>(material);
        p.smoothing_length[id] = eta * std::cbrt(q.volume);
        p.viscosity_alpha[id] = alpha;
        volume.push_back(q.volume);
        core.push_back(q.shell < 0);
      }
    }
  }

  // Lithostatic pressure at every particle, down its own column from the top of the material above it.
  // Where nothing but target lies above a particle (no boulder reaches above it in its column), the
  // column is the target from z = 0 down and the pressure depends on the depth alone: those depths are
  // integrated once, in order. Elsewhere the column is cut where it enters and leaves each boulder
  // (vertical_extent: every shape's section with a vertical line is one interval) and integrated
  // segment by segment through the material there, carrying the pressure across gaps.
  const Material& target = problem.materials[0];
  const std::size_t n = p.size();
  std::vector<double> pressure(n, 0.0);
  std::vector<bool> target_column(n, true);
  std::vector<VerticalExtent> extent(s.boulders.size());
  std::vector<double> depths;
  for (std::size_t i = 0; i < n; ++i) {
    for (const auto& b : s.boulders) {
      const VerticalExtent e = vertical_extent(b.shape, p.x[i], p.y[i]);
      if (!e.empty() && e.high > p.z[i]) target_column[i] = false;
    }
    if (target_column[i]) depths.push_back(-p.z[i]);
  }
  std::sort(depths.begin(), depths.end());
  depths.erase(std::unique(depths.begin(), depths.end()), depths.end());
  std::vector<double> depth_pressure(depths.size());
  double above = 0.0, depth_above = 0.0;
  for (std::size_t k = 0; k < depths.size(); ++k) {
    above = lithostatic_pressure_adaptive(target, above, depths[k] - depth_above, g);
    depth_above = depths[k];
    depth_pressure[k] = above;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (target_column[i]) {
      const auto it = std::lower_bound(depths.begin(), depths.end(), -p.z[i]);
      pressure[i] = depth_pressure[static_cast<std::size_t>(it - depths.begin())];
      continue;
    }
    const double x = p.x[i], y = p.y[i], z = p.z[i];
    const double top = std::sqrt(std::max(0.0, R * R - x * x - y * y));  // the domain's edge
    std::vector<double> cuts{0.0};
    for (std::size_t b = 0; b < s.boulders.size(); ++b) {
      extent[b] = vertical_extent(s.boulders[b].shape, x, y);
      if (extent[b].empty()) continue;
      cuts.push_back(extent[b].low);
      cuts.push_back(extent[b].high);
    }
    std::vector<double> levels{top, z};
    for (const double c : cuts) {
      if (c > z && c < top) levels.push_back(c);
    }
    std::sort(levels.begin(), levels.end(), std::greater<>());
    double column = 0.0;
    for (std::size_t k = 0; k + 1 < levels.size(); ++k) {
      const double high = levels[k], low = levels[k + 1];
      if (!(high > low)) continue;
      const double middle = 0.5 * (high + low);
      int material = -1;
      for (std::size_t b = 0; b < s.boulders.size(); ++b) {
        if (!extent[b].empty() && extent[b].low < middle && middle < extent[b].high) {
          material = static_cast<int>(2 + b);
          break;
        }
      }
      if (material < 0 && middle < 0.0) material = 0;
      if (material < 0) continue;  // empty space: the pressure carries over
      column = lithostatic_pressure_adaptive(problem.materials[static_cast<std::size_t>(material)], column,
                                             high - low, g);
    }
    pressure[i] = column;
  }

  // State, mass, fixed shell, counts.
  const double inner2 = (R - shell) * (R - shell);
  for (std::size_t i = 0; i < n; ++i) {
    const Material& m = problem.materials[p.material[i]];
    const LithostaticState state = lithostatic_state(m, pressure[i]);
    p.mass[i] = state.density * volume[i];
    set_state(p, i, m, state.density, state.distention);
    if (p.x[i] * p.x[i] + p.y[i] * p.y[i] + p.z[i] * p.z[i] > inner2) {
      p.flags[i] |= particle_fixed;
      ++summary.fixed_particles;
    }
    if (p.material[i] == 0) {
      ++summary.target_particles;
    } else {
      ++summary.boulder_particles[p.material[i] - 2u];
    }
    if (core[i]) ++summary.core_particles;
    summary.max_lithostatic_pressure = std::max(summary.max_lithostatic_pressure, p.pressure[i]);
    summary.min_smoothing_length = std::min(summary.min_smoothing_length, p.smoothing_length[i]);
    summary.max_smoothing_length = std::max(summary.max_smoothing_length, p.smoothing_length[i]);
  }
}

}  // namespace

std::string symmetry_name(DomainSymmetry symmetry) {
  return symmetry == DomainSymmetry::quarter ? "quarter" : "full";
}

std::string projectile_model_name(ProjectileModel model) {
  return model == ProjectileModel::resolved ? "resolved" : "point_source_stand_in";
}

Material density_scaled_material(const Material& material, double k) {
  if (k == 1.0) return material;
  Material out = material;
  out.name = material.name + "_stand_in";
  out.description = material.description +
                    " [density-scaled point-source stand-in: density and every "
                    "stress-like parameter x " +
                    number_text(k) + "]";
  std::visit(
      [k](auto& law) {
        using Law = std::decay_t<decltype(law)>;
        if constexpr (std::is_same_v<Law, Tillotson>) {
          law.reference_density *= k;
          law.A *= k;
          law.B *= k;
        } else if constexpr (std::is_same_v<Law, LowSoundSpeed>) {
          law.reference_density *= k;
          law.A *= k;
        }
        // IdealGas: P = (gamma - 1) rho E scales with rho by itself.
      },
      out.eos);
  out.shear_modulus *= k;
  if (out.strength) {
    std::visit(
        [k](auto& law) {
          using Law = std::decay_t<decltype(law)>;
          if constexpr (std::is_same_v<Law, LundborgStrength>) {
            law.cohesion *= k;
            law.limiting_strength *= k;
          } else {
            law.yield_strength *= k;
          }
        },
        *out.strength);
  }
  if (out.porosity) {
    out.porosity->crush_curve.elastic_pressure *= k;
    out.porosity->crush_curve.transition_pressure *= k;
    out.porosity->crush_curve.solid_pressure *= k;
  }
  return out;
}

ImpactSummary impact_projectile_summary(const ImpactSetup& s, double projectile_reference_density) {
  require_positive(s.projectile_mass, "impact.projectile_mass");
  require_positive(s.projectile_density, "impact.projectile_density");
  require_positive(s.impact_speed, "impact.impact_speed");
  require_positive(s.particle_spacing, "impact.particle_spacing");
  require_in_range(s.impact_angle, "impact.impact_angle (degrees)", 0.0, 90.0, false, true);
  require_in_range(s.coupling_exponent, "impact.coupling_exponent", 0.0, 1.0, true);
  validate_grading(s);
  ImpactSummary out;
  const double pi = std::numbers::pi;
  const double dx = projectile_spacing(s);
  const double minimum = min_projectile_radius_in_spacings * dx;
  const std::string spacing_key = is_graded(s) ? "inner_spacing" : "particle_spacing";
  out.projectile_mass = s.projectile_mass;
  out.projectile_density = s.projectile_density;
  out.projectile_radius = std::cbrt(3.0 * s.projectile_mass / (4.0 * pi * s.projectile_density));
  out.impact_speed = s.impact_speed;
  out.impact_angle = s.impact_angle;
  const double theta = s.impact_angle * pi / 180.0;
  out.impact_velocity = {s.impact_speed * std::sin(theta), 0.0, -s.impact_speed * std::cos(theta)};
  out.model = s.projectile_model;
  out.coupling_exponent = s.coupling_exponent;
  const double a = out.projectile_radius;
  if (s.projectile_model == ProjectileModel::resolved) {
    if (a < minimum * (1.0 - 1e-12)) {
      fail(spacing_key,
           "value " + number_text(dx) + " does not resolve the projectile of radius a = " + number_text(a) +
               " m (needs a >= " + number_text(min_projectile_radius_in_spacings) +
               " particle spacings): use projectile_model = \"point_source_stand_in\", a "
               "spacing <= " +
               number_text(a / min_projectile_radius_in_spacings) + " m" +
               (is_graded(s) ? std::string() : " or a graded target with inner_spacing <= that"));
    }
    out.model_radius = a;
    out.model_density = s.projectile_density;
    out.model_mass = s.projectile_mass;
  } else {
    double radius = s.stand_in_radius > 0.0 ? s.stand_in_radius : std::max(a, minimum);
    if (!std::isfinite(radius) || radius < minimum * (1.0 - 1e-12)) {
      fail("stand_in_radius", "value " + number_text(s.stand_in_radius) +
                                  " out of range: the stand-in needs a "
                                  "radius >= " +
                                  number_text(min_projectile_radius_in_spacings) + " " + spacing_key + " = " +
                                  number_text(minimum) + " m (0: max(a, 2 dx))");
    }
    // Same a delta^nu at the same U (docs/physics.md section 4): delta_s = delta (a/a_s)^(1/nu).
    out.model_radius = radius;
    out.model_density = s.projectile_density * std::pow(a / radius, 1.0 / s.coupling_exponent);
    out.model_mass = 4.0 / 3.0 * pi * radius * radius * radius * out.model_density;
  }
  out.model_density_scale = out.model_density / projectile_reference_density;
  // Touching: the continuum sphere touches the plane z = 0 at the impact point.
  out.projectile_centre = {0.0, 0.0, out.model_radius};
  return out;
}

ImpactScenario make_impact(const ImpactSetup& s, double eta, double alpha,
                           const std::array<double, 3>& gravity) {
  if (gravity[0] != 0.0 || gravity[1] != 0.0 || !(gravity[2] <= 0.0) || !std::isfinite(gravity[2])) {
    throw InputError("run.gravity: the impact set-up needs vertical gravity [0, 0, -g] with g >= 0, got [" +
                     number_text(gravity[0]) + ", " + number_text(gravity[1]) + ", " +
                     number_text(gravity[2]) + "]");
  }
  require_positive(s.domain_radius, "impact.domain_radius");
  require_positive(s.particle_spacing, "impact.particle_spacing");
  validate_grading(s);
  require_positive(s.low_sound_speed_modulus, "impact.A_low");
  if (!(s.escape_speed >= 0.0) || !std::isfinite(s.escape_speed)) {
    fail("escape_speed",
         "value " + number_text(s.escape_speed) + " out of range: must be >= 0 (0: not used)");
  }
  if (!(s.transition_time >= 0.0) || !std::isfinite(s.transition_time)) {
    fail("t_transition",
         "value " + number_text(s.transition_time) + " out of range: must be >= 0 (0: 10 R_dom / c)");
  }
  require_non_negative(s.fixed_shell_thickness, "impact.fixed_shell_thickness");
  const double g = -gravity[2];
  const double dx = s.particle_spacing;
  const double R = s.domain_radius;
  const double h = eta * dx;
  // The smoothing length at the boundary: of dx_max, or with the far coarsening of the spacing at R_dom.
  const GradedSpacing local = graded_spacing_of(s);
  const double h_edge = local.coarsened() ? eta * local.at(R) : h;
  const double shell = s.fixed_shell_thickness > 0.0 ? s.fixed_shell_thickness : 2.0 * h_edge;
  if (s.fixed_shell_thickness > 0.0 && shell < 2.0 * h_edge * (1.0 - 1e-12)) {
    fail("fixed_shell_thickness", "value " + number_text(shell) +
                                      " out of range: at least two smoothing lengths at R_dom, 2 eta dx = " +
                                      number_text(2.0 * h_edge) + " m");
  }
  if (R < 4.0 * shell) {
    fail("domain_radius", "value " + number_text(R) + " too small: at least 4 fixed-shell thicknesses (" +
                              number_text(4.0 * shell) + " m) at this particle spacing");
  }
  const double estimate = 2.0 / 3.0 * std::numbers::pi * std::pow(R / dx, 3) /
                          (s.symmetry == DomainSymmetry::quarter ? 4.0 : 1.0);
  if (!is_graded(s) && estimate > 4e8) {
    fail("particle_spacing", "value " + number_text(dx) + " would give about " + number_text(estimate) +
                                 " target particles (at most 4e8)");
  }
  if (s.symmetry == DomainSymmetry::quarter) {
    if (s.impact_angle != 0.0) {
      fail("symmetry",
           "\"quarter\" needs a vertical impact (impact_angle = 0), got " + number_text(s.impact_angle));
    }
    if (!s.boulders.empty()) {
      fail("symmetry",
           "\"quarter\" cannot take boulders: the mirror planes x = 0 and y = 0 would mirror them too");
    }
  }

  ImpactScenario scenario;
  ProblemSetup& problem = scenario.problem;
  problem.materials.push_back(load_material(s.target_material));
  const Material projectile_material = load_material(s.projectile_material);
  ImpactSummary summary =
      impact_projectile_summary(s, reference_density(projectile_material, "projectile_material"));
  problem.materials.push_back(density_scaled_material(projectile_material, summary.model_density_scale));
  for (std::size_t b = 0; b < s.boulders.size(); ++b) {
    if (s.boulders[b].shape.parts.empty()) fail("boulders[" + std::to_string(b) + "]", "has no shape");
    problem.materials.push_back(load_material(s.boulders[b].material));
    (void)reference_density(problem.materials.back(), "boulders[" + std::to_string(b) + "].material");
    summary.boulder_names.push_back(s.boulders[b].name);
    summary.boulder_material_ids.push_back(static_cast<std::uint16_t>(2 + b));
  }
  const Material& target = problem.materials[0];
  (void)reference_density(target, "target_material");
  const LithostaticState surface = lithostatic_state(target, 0.0);

  summary.domain_radius = R;
  summary.particle_spacing = dx;
  summary.fixed_shell_thickness = shell;
  summary.smoothing_length = h;
  summary.gravity = g;
  summary.initial_bulk_density = surface.density;
  summary.initial_distention = surface.distention;
  summary.initial_sound_speed =
      evaluate_material(target, surface.density, 0.0, surface.distention, 0.0).sound_speed;
  summary.symmetry = s.symmetry;
  summary.transition_time_from_rule = !(s.transition_time > 0.0);
  summary.transition_time =
      summary.transition_time_from_rule ? 10.0 * R / summary.initial_sound_speed : s.transition_time;
  summary.low_sound_speed_modulus = s.low_sound_speed_modulus;
  summary.escape_speed = s.escape_speed;
  summary.boulder_particles.assign(s.boulders.size(), 0);
  summary.inner_spacing = projectile_spacing(s);
  summary.min_smoothing_length = summary.max_smoothing_length = h;

  Particles& p = problem.particles;
  if (is_graded(s)) {
    build_graded_target(s, eta, alpha, g, shell, problem, summary);
  } else {
    build_lattice_target(s, alpha, g, shell, problem, summary);
  }

  // No boulder may reach into the projectile's sphere (plus half a spacing: the particles' cells; on a
  // graded target the core's, where the projectile is).
  const double dx_p = summary.inner_spacing;
  const auto& c = summary.projectile_centre;
  const double clearance = summary.model_radius + 0.5 * dx_p * (1.0 - 1e-9);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double d = std::hypot(p.x[i] - c[0], p.y[i] - c[1], p.z[i] - c[2]);
    if (d < clearance) {
      const std::size_t b = p.material[i] >= 2 ? p.material[i] - 2u : 0;
      fail(p.material[i] >= 2 ? "boulders[" + std::to_string(b) + "]" : "projectile",
           "overlaps the projectile sphere (centre z = " + number_text(c[2]) + " m, radius " +
               number_text(summary.model_radius) + " m)");
    }
  }

  // Projectile: offset cubic lattice centred on the sphere's centre; equal masses m_model / N over the
  // N nodes of the full sphere.
  const Material& projectile = problem.materials[1];
  const double projectile_distention =
      projectile.porosity ? projectile.porosity->crush_curve.initial_distention : 1.0;
  std::vector<std::array<double, 3>> nodes;
  const auto np = static_cast<long>(std::ceil(summary.model_radius / dx_p)) + 1;
  const double a2 = summary.model_radius * summary.model_radius;
  for (long i = -np; i < np; ++i) {
    for (long j = -np; j < np; ++j) {
      for (long k = -np; k < np; ++k) {
        const double ox = (static_cast<double>(i) + 0.5) * dx_p, oy = (static_cast<double>(j) + 0.5) * dx_p,
                     oz = (static_cast<double>(k) + 0.5) * dx_p;
        if (ox * ox + oy * oy + oz * oz < a2) nodes.push_back({ox, oy, oz});
      }
    }
  }
  const double particle_mass = summary.model_mass / static_cast<double>(nodes.size());
  const double projectile_h = eta * std::cbrt(particle_mass / summary.model_density);
  for (const auto& o : nodes) {
    if (s.symmetry == DomainSymmetry::quarter && (o[0] < 0.0 || o[1] < 0.0)) continue;
    const std::size_t id = add_particle(p, c[0] + o[0], c[1] + o[1], c[2] + o[2]);
    p.material[id] = 1;
    p.mass[id] = particle_mass;
    p.smoothing_length[id] = projectile_h;
    p.viscosity_alpha[id] = alpha;
    p.vx[id] = summary.impact_velocity[0];
    p.vy[id] = summary.impact_velocity[1];
    p.vz[id] = summary.impact_velocity[2];
    set_state(p, id, projectile, summary.model_density, projectile_distention);
    ++summary.projectile_particles;
  }
  summary.total_particles = p.size();

  // Open box (no periodic axis): the bounding box of the set-up, for reference only, except that the
  // quarter domain's planes x = 0 and y = 0 are mirror planes (the engine's neighbour search adds the
  // mirror images of the missing three quarters, mirror_image.hpp).
  const bool quarter = s.symmetry == DomainSymmetry::quarter;
  const double low = quarter ? 0.0 : -R;
  problem.box.lower = {low, low, -R};
  problem.box.upper = {R, R, std::max(R, c[2] + summary.model_radius)};
  problem.box.periodic = {false, false, false};
  problem.box.mirror = {quarter, quarter, false};
  scenario.summary = std::move(summary);
  return scenario;
}

std::string describe_impact(const ImpactSummary& s) {
  std::ostringstream o;
  o.precision(4);
  o << "impact: projectile m = " << s.projectile_mass << " kg, delta = " << s.projectile_density
    << " kg/m^3, a = " << s.projectile_radius << " m, U = " << s.impact_speed << " m/s at " << s.impact_angle
    << " deg from vertical\n";
  if (s.model == ProjectileModel::point_source_stand_in) {
    const double factor = s.model_mass / s.projectile_mass;
    o << "impact: point-source stand-in (same a delta^nu, nu = " << s.coupling_exponent << "): radius "
      << s.model_radius << " m, density " << s.model_density << " kg/m^3, mass " << s.model_mass
      << " kg (momentum and energy x " << factor << "), material density scale " << s.model_density_scale
      << "\n";
  } else {
    o << "impact: resolved projectile\n";
  }
  o << "impact: target R_dom = " << s.domain_radius << " m, dx = " << s.particle_spacing << " m, fixed shell "
    << s.fixed_shell_thickness << " m, symmetry " << symmetry_name(s.symmetry)
    << (s.symmetry == DomainSymmetry::quarter ? " (mirror planes x = 0, y = 0)" : "")
    << ", rho_bulk = " << s.initial_bulk_density << " kg/m^3, c = " << s.initial_sound_speed
    << " m/s, g = " << s.gravity << " m/s^2, max lithostatic P = " << s.max_lithostatic_pressure << " Pa\n";
  if (s.graded) {
    const GradedSpacing spacing{s.inner_spacing, s.inner_radius, s.grading, s.particle_spacing};
    o << "impact: graded target: core dx0 = " << s.inner_spacing << " m for r < " << s.inner_radius << " m ("
      << s.core_particles << " particles), then " << s.shells << " shells growing by " << s.grading
      << " per spacing (dx = dx0 + " << spacing.slope() << " (r - " << s.inner_radius + 0.5 * s.inner_spacing
      << " m))";
    if (s.graded_shells < s.shells) {
      o << " to dx_max = " << s.particle_spacing << " m at r = " << s.graded_radius << " m ("
        << s.graded_shells << " graded shells)";
      if (s.coarse_shells > 0) {
        o << ", growing again from r = " << s.far_shells_radius << " m towards dx_far = " << s.far_spacing
          << " m (" << s.coarse_shells << " shells, far_radius " << s.far_radius << " m)";
      }
    } else {
      o << ", reaching dx = " << spacing.at(s.domain_radius) << " m at R_dom (dx_max = " << s.particle_spacing
        << " m not reached)";
    }
    o << "; dx(1 m) = " << spacing.at(1.0) << " m, h from " << s.min_smoothing_length << " to "
      << s.max_smoothing_length << " m\n";
  }
  o << "impact: particles " << s.total_particles << " (target " << s.target_particles << ", projectile "
    << s.projectile_particles;
  for (std::size_t b = 0; b < s.boulder_names.size(); ++b) {
    o << ", boulder " << s.boulder_names[b] << " " << s.boulder_particles[b];
  }
  o << "; fixed " << s.fixed_particles << ")\n";
  o << "impact: t_transition = " << s.transition_time << " s"
    << (s.transition_time_from_rule ? " (10 R_dom / c)" : " (given)")
    << ", A_low = " << s.low_sound_speed_modulus << " Pa\n";
  o << "impact: ejecta leave the hydrodynamics beyond R_dom = " << s.domain_radius << " m";
  if (s.escape_speed > 0.0) o << " or when faster than " << s.escape_speed << " m/s and clear of the target";
  o << "\n";
  return o.str();
}

}  // namespace craterkit::impact
