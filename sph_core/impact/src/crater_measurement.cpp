// Crater measurement (docs/physics.md section 5); the method and its choices are described in
// crater_measurement.hpp and docs/crater_measurement.md. The density on the sample columns and the
// surface height on each are in crater_columns.hpp; this file turns them into the crater, step by step
// (measure()).
#include "craterkit/impact/crater_measurement.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <span>
#include <sstream>
#include <utility>

#include <nlohmann/json.hpp>

#include "crater_columns.hpp"
#include "craterkit/common/atomic_file.hpp"
#include "craterkit/common/checks.hpp"
#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"

namespace craterkit::impact {

using namespace sph;
namespace {

using crater_detail::bisection_steps;
using crater_detail::Column;
using crater_detail::column_density;
using crater_detail::column_surface;
using crater_detail::ColumnGrid;
using crater_detail::nan;

// The steps that follow the local spacing dx(r) (graded_spacing.hpp; the particle spacing everywhere on
// a uniform target): a defaulted step is taken at each sample radius from dx(r), so that a graded target
// is measured at its own resolution at every radius; an explicit one stays uniform.
struct LocalSteps {
  GradedSpacing local;
  bool graded_radial = false, graded_vertical = false, graded_wall = false;
  double vertical_step = 0.0, wall_depth = 0.0;  // m, the uniform values (at the centre when graded)

  // Downward scan step of the surface search on the column at radius r.
  [[nodiscard]] double vertical_step_at(double r) const {
    return graded_vertical ? 0.25 * local.at(r) : vertical_step;
  }
  // Depth below z = 0 that makes the sample at radius r part of the crater wall.
  [[nodiscard]] double wall_depth_at(double r) const { return graded_wall ? local.at(r) : wall_depth; }
};

// Resolves the defaulted settings and records them in m (their values at the centre on a graded target);
// returns the rules for the steps that vary with the radius.
LocalSteps resolve_settings(const CraterMeasurementOptions& o, CraterMeasurement& m) {
  m.rho_initial = o.rho_initial;
  m.rho_crit = 0.5 * o.rho_initial;
  m.particle_spacing = o.particle_spacing;
  m.kernel = o.kernel;
  m.centre = o.centre;
  m.quarter_symmetric = o.quarter_symmetric;
  const GradedSpacing local{o.inner_spacing,    o.inner_radius, o.grading,
                            o.particle_spacing, o.far_radius,   o.far_spacing};
  const double spacing0 = local.at(0.0);
  m.inner_spacing = local.graded() ? o.inner_spacing : o.particle_spacing;
  m.inner_radius = local.graded() ? o.inner_radius : 0.0;
  m.grading = local.graded() ? o.grading : 0.0;
  m.radial_step = o.radial_step > 0.0 ? o.radial_step : 0.25 * spacing0;
  m.vertical_step = o.vertical_step > 0.0 ? o.vertical_step : 0.25 * spacing0;
  m.wall_depth = o.wall_depth > 0.0 ? o.wall_depth : spacing0;
  LocalSteps steps;
  steps.local = local;
  steps.graded_radial = local.graded() && !(o.radial_step > 0.0);
  steps.graded_vertical = local.graded() && !(o.vertical_step > 0.0);
  steps.graded_wall = local.graded() && !(o.wall_depth > 0.0);
  steps.vertical_step = m.vertical_step;
  steps.wall_depth = m.wall_depth;
  return steps;
}

// The mass of the particles flagged ejected, in total and per material id; on a quarter domain the full
// crater's, four times the quarter's (the particle count stays the file's).
void measure_ejecta(const Particles& p, bool quarter_symmetric, CraterMeasurement& m) {
  std::map<int, double> ejected_by_material;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if ((p.flags[i] & particle_ejected) == 0) continue;
    m.ejected_mass += p.mass[i];
    ++m.ejected_particles;
    ejected_by_material[p.material[i]] += p.mass[i];
  }
  if (quarter_symmetric) {
    m.ejected_mass *= 4.0;
    for (auto& entry : ejected_by_material) entry.second *= 4.0;
  }
  m.ejected_mass_by_material.assign(ejected_by_material.begin(), ejected_by_material.end());
}

// On a quarter domain, warns when particles lie more than a spacing outside the quarter: their mirror
// images would overlap the target, which suggests a full-domain run measured as a quarter.
void warn_outside_quarter(const Particles& p, const CraterMeasurementOptions& o,
                          std::vector<std::string>& warnings) {
  std::size_t outside = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if ((p.flags[i] & particle_ejected) == 0 &&
        (p.x[i] < o.centre[0] - o.particle_spacing || p.y[i] < o.centre[1] - o.particle_spacing)) {
      ++outside;
    }
  }
  if (outside > 0) {
    warnings.push_back("quarter_symmetric: " + std::to_string(outside) +
                       " particles lie outside the quarter x >= centre x, y >= centre y; their mirror "
                       "images overlap the target (is this a full-domain run?)");
  }
}

// The default outer end of the rays: the smallest horizontal extent of the non-ejected particles along
// +-x and +-y from the centre, less 2 h_cell and one spacing, so that the rounded outer edge of the
// target is never taken for a crater wall. Throws when that leaves fewer than four radial steps.
double default_max_radius(const Particles& p, const CraterMeasurementOptions& o, double h_cell,
                          double radial_step) {
  double extent = std::numeric_limits<double>::infinity();
  std::array<double, 4> far{-extent, -extent, -extent, -extent};
  for (std::size_t i = 0; i < p.size(); ++i) {
    if ((p.flags[i] & particle_ejected) != 0) continue;
    far[0] = std::max(far[0], p.x[i] - o.centre[0]);
    far[1] = std::max(far[1], o.centre[0] - p.x[i]);
    far[2] = std::max(far[2], p.y[i] - o.centre[1]);
    far[3] = std::max(far[3], o.centre[1] - p.y[i]);
  }
  if (o.quarter_symmetric) {  // the mirror images reach as far as the quarter
    far[1] = far[0];
    far[3] = far[2];
  }
  for (const double f : far) extent = std::min(extent, f);
  const double max_radius = extent - 2.0 * h_cell - o.particle_spacing;
  if (!(max_radius > 4.0 * radial_step)) {
    throw InputError("max_radius: the target extends only " + format_number(extent) +
                     " m from the centre; give max_radius explicitly");
  }
  return max_radius;
}

// The polar sample grid: n_azimuths rays at azimuths a dphi (from +x towards +y), each sampled at the
// middles r_k of radial cells of width w_k.
struct PolarGrid {
  std::size_t n_azimuths = 0;
  double dphi = 0.0;                  // rad
  std::vector<double> radius, width;  // m, r_k and w_k
  [[nodiscard]] std::size_t n_radii() const { return radius.size(); }
};

// The radial cells: uniform, w_k = dr; or on a graded target with the defaulted step, w_k = dx(inner
// edge of the cell) / 4, so that the sampling follows the local resolution. Throws when fewer than four
// cells fit within max_radius.
PolarGrid polar_grid(const LocalSteps& steps, double max_radius, double radial_step, std::size_t n_azimuths) {
  PolarGrid g;
  if (steps.graded_radial) {
    for (double edge = 0.0;;) {
      const double w = 0.25 * steps.local.at(edge);
      if (edge + w > max_radius) break;
      g.radius.push_back(edge + 0.5 * w);
      g.width.push_back(w);
      edge += w;
    }
  } else {
    // A bound on the samples per ray, so that a tiny step is an error rather than gigabytes of samples.
    constexpr double max_radial_samples = 1e5;
    if (!(max_radius / radial_step <= max_radial_samples)) {
      throw InputError(
          "radial_step " + format_number(radial_step) + " m: " + format_number(max_radius / radial_step) +
          " samples per ray up to max_radius " + format_number(max_radius) +
          " m; allowed at most 1e5, i.e. radial_step >= " + format_number(max_radius / max_radial_samples) +
          " m");
    }
    const auto count = static_cast<std::size_t>(std::floor(max_radius / radial_step));
    for (std::size_t k = 0; k < count; ++k) {
      g.radius.push_back((double(k) + 0.5) * radial_step);
      g.width.push_back(radial_step);
    }
  }
  if (g.n_radii() < 4) {
    throw InputError("max_radius " + format_number(max_radius) + " m: fewer than 4 radial steps");
  }
  g.n_azimuths = n_azimuths;
  g.dphi = 2.0 * std::numbers::pi / double(n_azimuths);
  return g;
}

// The surface height z_s and the density on the pre-impact plane z = 0 on every sample column, ray
// after ray: sample (a, k) at index a * n_radii + k.
struct SurfaceSamples {
  std::vector<double> height, plane_density;
  std::size_t n_radii = 0;

  [[nodiscard]] std::span<const double> ray_height(std::size_t a) const {
    return {height.data() + a * n_radii, n_radii};
  }
  [[nodiscard]] std::span<const double> ray_plane_density(std::size_t a) const {
    return {plane_density.data() + a * n_radii, n_radii};
  }
};

// Samples every column of the polar grid. This is the bulk of the cost; the columns are independent.
template <class Kernel>
SurfaceSamples sample_surface(const ColumnGrid& grid, const std::array<double, 2>& centre, const PolarGrid& g,
                              const LocalSteps& steps, double rho_crit) {
  const std::size_t nr = g.n_radii(), n = g.n_azimuths * nr;
  SurfaceSamples samples;
  samples.n_radii = nr;
  samples.height.resize(n);
  samples.plane_density.resize(n);
#pragma omp parallel
  {
    Column column;
#pragma omp for schedule(dynamic, 16)
    for (std::size_t s = 0; s < n; ++s) {
      const std::size_t a = s / nr, k = s % nr;
      const double phi = g.dphi * double(a), r = g.radius[k];
      const double x = centre[0] + r * std::cos(phi), y = centre[1] + r * std::sin(phi);
      grid.gather(x, y, column);
      samples.height[s] = column_surface<Kernel>(column, rho_crit, steps.vertical_step_at(r));
      samples.plane_density[s] = column_density<Kernel>(column, 0.0);
    }
  }
  return samples;
}

// The crater wall on one ray: the outermost sample whose surface lies more than the wall depth below
// z = 0. The edge search never looks inside it, so a fallback clump on the floor cannot be taken for
// the edge.
std::optional<std::size_t> wall_sample(std::span<const double> zs, const PolarGrid& g,
                                       const LocalSteps& steps) {
  for (std::size_t k = zs.size(); k-- > 0;) {
    if (std::isfinite(zs[k]) && zs[k] < -steps.wall_depth_at(g.radius[k])) return k;
  }
  return std::nullopt;
}

// The rim crest on one ray: the highest surface sample outside the wall (the innermost of equal ones).
std::optional<std::size_t> crest_sample(std::span<const double> zs, std::size_t wall) {
  std::optional<std::size_t> crest;
  for (std::size_t k = wall + 1; k < zs.size(); ++k) {
    if (std::isfinite(zs[k]) && (!crest || zs[k] > zs[*crest])) crest = k;
  }
  return crest;
}

// The first sample going outward from the wall, up to the crest, where the plane density reaches
// rho_crit: the crater wall meets the pre-impact plane between it and the sample before it. The crossing
// next to the wall rather than the outermost one keeps the edge defined when the rim is low (an
// undisturbed plane reads rho_crit up to lattice noise).
std::optional<std::size_t> plane_crossing_sample(std::span<const double> rho0, std::size_t wall,
                                                 std::size_t crest, double rho_crit) {
  for (std::size_t k = wall + 1; k <= crest; ++k) {
    if (rho0[k] >= rho_crit) return k;
  }
  return std::nullopt;
}

// The radius between lo and hi (rho(lo) < rho_crit <= rho(hi) on z = 0) where the plane density along
// the ray at `azimuth` crosses rho_crit, by bisection.
template <class Kernel>
double bisect_edge(const ColumnGrid& grid, const std::array<double, 2>& centre, double azimuth, double lo,
                   double hi, double rho_crit) {
  const double ca = std::cos(azimuth), sa = std::sin(azimuth);
  for (int it = 0; it < bisection_steps; ++it) {
    const double mid = 0.5 * (lo + hi);
    const double rho = grid.density_at<Kernel>(centre[0] + mid * ca, centre[1] + mid * sa, 0.0);
    (rho >= rho_crit ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

// The crater edge along ray a, searched inward from the rim crest: the wall, the crest outside it, then
// the plane crossing next to the wall, bisected. The ray has no edge (NaN) when it has no wall, no
// surface outside the wall, or no crossing before the crest; what was not found stays NaN.
template <class Kernel>
RayMeasurement measure_ray(const ColumnGrid& grid, const std::array<double, 2>& centre, const PolarGrid& g,
                           const SurfaceSamples& samples, const LocalSteps& steps, double rho_crit,
                           std::size_t a) {
  RayMeasurement ray;
  ray.azimuth = g.dphi * double(a);
  ray.edge_radius = ray.crest_radius = ray.crest_height = ray.wall_radius = nan;
  const std::span<const double> zs = samples.ray_height(a);
  const std::optional<std::size_t> wall = wall_sample(zs, g, steps);
  if (!wall) return ray;
  ray.wall_radius = g.radius[*wall];
  const std::optional<std::size_t> crest = crest_sample(zs, *wall);
  if (!crest) return ray;
  ray.crest_radius = g.radius[*crest];
  ray.crest_height = zs[*crest];
  const std::optional<std::size_t> edge =
      plane_crossing_sample(samples.ray_plane_density(a), *wall, *crest, rho_crit);
  if (!edge) return ray;
  ray.edge_radius =
      bisect_edge<Kernel>(grid, centre, ray.azimuth, g.radius[*edge - 1], g.radius[*edge], rho_crit);
  return ray;
}

// The rays of the four axis directions +x, -x, +y, -y (the order of CraterMeasurement::radii).
constexpr std::array<const char*, 4> direction_names{"+x", "-x", "+y", "-y"};
std::array<std::size_t, 4> direction_rays(std::size_t n_azimuths) {
  return {0, n_azimuths / 2, n_azimuths / 4, 3 * n_azimuths / 4};
}

// The four directional radii, and the warnings about the edges: a direction without an edge, a
// direction whose rim crest is too low for a well-conditioned edge, rays without an edge.
void directional_radii(CraterMeasurement& m, const GradedSpacing& local) {
  const std::size_t na = m.rays.size();
  const std::array<std::size_t, 4> direction_ray = direction_rays(na);
  for (std::size_t d = 0; d < 4; ++d) {
    m.radii[d] = m.rays[direction_ray[d]].edge_radius;
    if (!std::isfinite(m.radii[d])) {
      m.warnings.push_back(
          std::string("no crater edge along ") + direction_names[d] +
          ": the surface never lies more than wall_depth = " + format_number(m.wall_depth) +
          " m below z = 0 within max_radius, or the wall does not reach z = 0 before the crest");
    }
  }
  for (std::size_t d = 0; d < 4; ++d) {
    const RayMeasurement& ray = m.rays[direction_ray[d]];
    if (std::isfinite(m.radii[d]) && ray.crest_height < 0.25 * local.at(ray.crest_radius)) {
      m.warnings.push_back(
          std::string("rim crest along ") + direction_names[d] + " only " + format_number(ray.crest_height) +
          " m above z = 0 (< local spacing/4): without a rim the plane density approaches rho_crit "
          "from below outside the wall, so the edge is ill-conditioned (up to 2 h too large)");
    }
  }
  const auto missing =
      static_cast<std::size_t>(std::count_if(m.rays.begin(), m.rays.end(), [](const RayMeasurement& ray) {
        return !std::isfinite(ray.edge_radius);
      }));
  if (missing > 0) {
    m.warnings.push_back(std::to_string(missing) + " of " + std::to_string(na) + " rays have no crater edge");
  }
}

// The crater radius, the mean of the four directional radii, its spread and uncertainty: the standard
// error of the mean and half the local spacing at the edge (the resolution of a particle surface),
// added in quadrature. NaN unless all four directions have an edge.
void mean_crater_radius(CraterMeasurement& m, const GradedSpacing& local) {
  if (!std::all_of(m.radii.begin(), m.radii.end(), [](double r) { return std::isfinite(r); })) {
    m.crater_radius = m.crater_radius_uncertainty = m.radius_spread = nan;
    return;
  }
  double mean = 0.0;
  for (const double r : m.radii) mean += 0.25 * r;
  double var = 0.0;
  for (const double r : m.radii) var += (r - mean) * (r - mean) / 3.0;
  m.crater_radius = mean;
  m.radius_spread = std::sqrt(var);
  const double dx_edge = local.at(mean);
  m.crater_radius_uncertainty = std::sqrt(0.25 * var + 0.25 * dx_edge * dx_edge);
}

// The shape of the outline over all rays: the mean edge radius, the shortest and longest edge and their
// azimuths, and the outline's centre offset, the first Fourier harmonic of the edge radius (NaN unless
// every ray has an edge).
void outline_shape(CraterMeasurement& m) {
  const std::size_t na = m.rays.size();
  double edge_sum = 0.0;
  std::size_t edge_count = 0;
  for (const auto& ray : m.rays) {
    if (std::isfinite(ray.edge_radius)) {
      edge_sum += ray.edge_radius;
      ++edge_count;
    }
  }
  m.mean_azimuthal_radius = edge_count ? edge_sum / double(edge_count) : nan;
  m.min_edge_radius = m.min_edge_azimuth = m.max_edge_radius = m.max_edge_azimuth = nan;
  double harmonic_x = 0.0, harmonic_y = 0.0;
  for (const auto& ray : m.rays) {
    if (!std::isfinite(ray.edge_radius)) continue;
    if (!(ray.edge_radius >= m.min_edge_radius)) {  // also replaces NaN
      m.min_edge_radius = ray.edge_radius;
      m.min_edge_azimuth = ray.azimuth;
    }
    if (!(ray.edge_radius <= m.max_edge_radius)) {
      m.max_edge_radius = ray.edge_radius;
      m.max_edge_azimuth = ray.azimuth;
    }
    harmonic_x += ray.edge_radius * std::cos(ray.azimuth);
    harmonic_y += ray.edge_radius * std::sin(ray.azimuth);
  }
  m.outline_centre_offset = edge_count == na && na > 0 ? std::array<double, 2>{2.0 * harmonic_x / double(na),
                                                                               2.0 * harmonic_y / double(na)}
                                                       : std::array<double, 2>{nan, nan};
}

// The apparent depth (the lowest surface sample inside the edge of its ray) and volume (sum of
// max(0, -z_s) r dr dphi over those samples): the cavity below the pre-impact plane, reduced by
// fallback. Both NaN when no ray has an edge.
void depth_and_volume(CraterMeasurement& m, const PolarGrid& g, const SurfaceSamples& samples) {
  double lowest = std::numeric_limits<double>::infinity();
  bool any_edge = false;
  m.volume = 0.0;
  for (std::size_t a = 0; a < g.n_azimuths; ++a) {
    const double edge = m.rays[a].edge_radius;
    if (!std::isfinite(edge)) continue;
    any_edge = true;
    const std::span<const double> zs = samples.ray_height(a);
    for (std::size_t k = 0; k < zs.size() && g.radius[k] < edge; ++k) {
      const double z = zs[k];
      if (!std::isfinite(z)) continue;
      lowest = std::min(lowest, z);
      m.volume += std::max(0.0, -z) * g.radius[k] * g.width[k] * g.dphi;
    }
  }
  m.depth = std::isfinite(lowest) ? -lowest : nan;
  if (!any_edge) m.volume = nan;
}

// The azimuthal profile (mean, min and max of z_s over the rays at each radius, NaN samples skipped) and
// the rim: the highest profile mean at or outside the crater radius.
void profile_and_rim(CraterMeasurement& m, const PolarGrid& g, const SurfaceSamples& samples) {
  const std::size_t nr = g.n_radii();
  m.profile.resize(nr);
  m.rim_height = m.rim_radius = nan;
  for (std::size_t k = 0; k < nr; ++k) {
    ProfileSample& ps = m.profile[k];
    ps.radius = g.radius[k];
    ps.min_height = std::numeric_limits<double>::infinity();
    ps.max_height = -std::numeric_limits<double>::infinity();
    double sum = 0.0;
    for (std::size_t a = 0; a < g.n_azimuths; ++a) {
      const double z = samples.height[a * nr + k];
      if (!std::isfinite(z)) continue;
      sum += z;
      ++ps.azimuths;
      ps.min_height = std::min(ps.min_height, z);
      ps.max_height = std::max(ps.max_height, z);
    }
    if (ps.azimuths == 0) {
      ps.mean_height = ps.min_height = ps.max_height = nan;
      continue;
    }
    ps.mean_height = sum / double(ps.azimuths);
    if (std::isfinite(m.crater_radius) && ps.radius >= m.crater_radius &&
        !(ps.mean_height <= m.rim_height)) {  // also replaces NaN
      m.rim_height = ps.mean_height;
      m.rim_radius = ps.radius;
    }
  }
}

double degrees(double radians) {
  return radians * (180.0 / std::numbers::pi);
}

// The wall's slope: the least-squares line z = a + b r through the azimuthal mean profile inside the crater
// radius, over the samples between 20 and 80 % of the depth below z = 0, which leave out the rounded edge
// and the floor; atan(b) in degrees (NaN without a depth or with fewer than three such samples).
void wall_slope(CraterMeasurement& m) {
  m.wall_slope = std::numeric_limits<double>::quiet_NaN();
  if (!(m.depth > 0.0) || !std::isfinite(m.crater_radius)) return;
  double n = 0.0, sum_r = 0.0, sum_z = 0.0;
  const auto in_band = [&](const ProfileSample& s) {
    return s.radius < m.crater_radius && s.mean_height >= -0.8 * m.depth && s.mean_height <= -0.2 * m.depth;
  };
  for (const ProfileSample& s : m.profile) {
    if (!in_band(s)) continue;
    n += 1.0;
    sum_r += s.radius;
    sum_z += s.mean_height;
  }
  if (n < 3.0) return;
  const double mean_r = sum_r / n, mean_z = sum_z / n;
  double srr = 0.0, srz = 0.0;
  for (const ProfileSample& s : m.profile) {
    if (!in_band(s)) continue;
    srr += (s.radius - mean_r) * (s.radius - mean_r);
    srz += (s.radius - mean_r) * (s.mean_height - mean_z);
  }
  if (srr > 0.0) m.wall_slope = degrees(std::atan(srz / srr));
}

// Where one boulder went: the mass-weighted centre of its non-ejected particles (selected by id, or by
// material id when it has no ids) minus its initial centre, and the mass of its ejected ones.
BoulderDisplacement track_boulder(const Particles& p, const BoulderSpec& spec) {
  BoulderDisplacement b;
  b.name = spec.name;
  b.initial_centre = spec.initial_centre;
  std::vector<std::uint64_t> ids = spec.ids;
  std::sort(ids.begin(), ids.end());
  std::array<double, 3> c{0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < p.size(); ++i) {
    const bool member = ids.empty() ? int(p.material[i]) == spec.material
                                    : std::binary_search(ids.begin(), ids.end(), p.id[i]);
    if (!member) continue;
    if ((p.flags[i] & particle_ejected) != 0) {
      b.ejected_mass += p.mass[i];
      continue;
    }
    ++b.particles;
    b.mass += p.mass[i];
    c[0] += p.mass[i] * p.x[i];
    c[1] += p.mass[i] * p.y[i];
    c[2] += p.mass[i] * p.z[i];
  }
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    b.centre[k] = b.mass > 0.0 ? c[k] / b.mass : nan;
    b.displacement[k] = b.centre[k] - b.initial_centre[k];
    d2 += b.displacement[k] * b.displacement[k];
  }
  b.displacement_magnitude = std::sqrt(d2);
  return b;
}

// The measurement, step by step: settings, ejecta, the density field, the sample grid and the surface on
// it, the edge of every ray, then what is derived from the edges and the surface.
template <class Kernel>
CraterMeasurement measure(const Particles& p, const CraterMeasurementOptions& o) {
  CraterMeasurement m;
  const LocalSteps steps = resolve_settings(o, m);
  measure_ejecta(p, o.quarter_symmetric, m);
  if (o.quarter_symmetric) warn_outside_quarter(p, o, m.warnings);

  const ColumnGrid grid(p, o.quarter_symmetric, o.centre);
  if (grid.count() == 0) throw InputError("particles: every particle is flagged ejected; nothing to measure");
  m.max_radius = o.max_radius > 0.0 ? o.max_radius : default_max_radius(p, o, grid.h_cell(), m.radial_step);
  const PolarGrid g = polar_grid(steps, m.max_radius, m.radial_step, o.n_azimuths);
  const SurfaceSamples samples = sample_surface<Kernel>(grid, o.centre, g, steps, m.rho_crit);

  m.rays.resize(g.n_azimuths);
  for (std::size_t a = 0; a < g.n_azimuths; ++a) {
    m.rays[a] = measure_ray<Kernel>(grid, o.centre, g, samples, steps, m.rho_crit, a);
  }
  directional_radii(m, steps.local);
  mean_crater_radius(m, steps.local);
  outline_shape(m);
  depth_and_volume(m, g, samples);
  profile_and_rim(m, g, samples);
  wall_slope(m);

  for (const auto& spec : o.boulders) {
    m.boulders.push_back(track_boulder(p, spec));
    if (m.boulders.back().particles == 0) {
      m.warnings.push_back("boulder " + spec.name + ": none of its particles remains");
    }
  }
  return m;
}

void validate(const CraterMeasurementOptions& o) {
  require_positive(o.rho_initial, "rho_initial");
  require_positive(o.particle_spacing, "particle_spacing");
  // 0 selects the default of each.
  require_non_negative(o.max_radius, "max_radius");
  require_non_negative(o.radial_step, "radial_step");
  require_non_negative(o.vertical_step, "vertical_step");
  require_non_negative(o.wall_depth, "wall_depth");
  if (!std::isfinite(o.centre[0]) || !std::isfinite(o.centre[1])) {
    throw InputError("centre: must be finite");
  }
  if (o.n_azimuths < 4 || o.n_azimuths % 4 != 0) {
    throw InputError("n_azimuths = " + std::to_string(o.n_azimuths) + ": must be a multiple of 4, >= 4");
  }
  for (const auto& b : o.boulders) {
    if (b.ids.empty() && b.material < 0) {
      throw InputError("boulder " + b.name + ": give its particle ids or a material id >= 0");
    }
  }
}

nlohmann::json array3(const std::array<double, 3>& v) {
  return nlohmann::json::array({v[0], v[1], v[2]});
}

// "directions": edge, crest and wall of the four axis rays.
nlohmann::json directions_json(const CraterMeasurement& m) {
  nlohmann::json directions = nlohmann::json::object();
  const std::size_t na = m.rays.size();
  if (na == 0) return directions;
  const std::array<std::size_t, 4> direction_ray = direction_rays(na);
  for (std::size_t d = 0; d < 4; ++d) {
    const auto& ray = m.rays[direction_ray[d]];
    directions[direction_names[d]] = {{"edge_radius", ray.edge_radius},
                                      {"crest_radius", ray.crest_radius},
                                      {"crest_height", ray.crest_height},
                                      {"wall_radius", ray.wall_radius}};
  }
  return directions;
}

// "outline": every ray's azimuth and edge, the crater's outline at the pre-impact level (null where a ray
// has no edge).
nlohmann::json outline_json(const CraterMeasurement& m) {
  nlohmann::json azimuths = nlohmann::json::array(), edges = nlohmann::json::array();
  for (const auto& ray : m.rays) {
    azimuths.push_back(degrees(ray.azimuth));
    edges.push_back(ray.edge_radius);
  }
  return {{"azimuth_deg", azimuths}, {"edge_radius", edges}};
}

nlohmann::json boulders_json(const CraterMeasurement& m) {
  nlohmann::json boulders = nlohmann::json::array();
  for (const auto& b : m.boulders) {
    boulders.push_back({{"name", b.name},
                        {"initial_centre", array3(b.initial_centre)},
                        {"centre", array3(b.centre)},
                        {"displacement", array3(b.displacement)},
                        {"displacement_magnitude", b.displacement_magnitude},
                        {"particles", b.particles},
                        {"mass", b.mass},
                        {"ejected_mass", b.ejected_mass}});
  }
  return boulders;
}

// "settings": the settings actually used, defaults resolved.
nlohmann::json settings_json(const CraterMeasurement& m) {
  return {{"rho_initial", m.rho_initial},
          {"rho_crit", m.rho_crit},
          {"particle_spacing", m.particle_spacing},
          {"kernel", std::string(kernel_name(m.kernel))},
          {"centre", {m.centre[0], m.centre[1]}},
          {"max_radius", m.max_radius},
          {"radial_step", m.radial_step},
          {"vertical_step", m.vertical_step},
          {"wall_depth", m.wall_depth},
          {"inner_spacing", m.inner_spacing},
          {"inner_radius", m.inner_radius},
          {"grading", m.grading},
          {"n_azimuths", m.rays.size()},
          {"quarter_symmetric", m.quarter_symmetric}};
}

}  // namespace

CraterMeasurement measure_crater(const Particles& particles, const CraterMeasurementOptions& options) {
  validate(options);
  return with_kernel(options.kernel,
                     [&](auto kernel) { return measure<decltype(kernel)>(particles, options); });
}

double interpolated_density_direct(const Particles& p, KernelType kernel, double x, double y, double z) {
  return with_kernel(kernel, [&](auto k) {
    using Kernel = decltype(k);
    double rho = 0.0;
    for (std::size_t j = 0; j < p.size(); ++j) {
      if ((p.flags[j] & particle_ejected) != 0) continue;
      const double dx = p.x[j] - x, dy = p.y[j] - y, dz = p.z[j] - z;
      rho += p.mass[j] * Kernel::value(std::sqrt(dx * dx + dy * dy + dz * dz), p.smoothing_length[j]);
    }
    return rho;
  });
}

std::vector<ColumnSample> sample_columns(const Particles& particles, KernelType kernel, double rho_crit,
                                         double vertical_step, const std::vector<std::array<double, 2>>& xy) {
  require_positive(rho_crit, "rho_crit");
  require_positive(vertical_step, "vertical_step");
  const ColumnGrid grid(particles, false, {0.0, 0.0});
  std::vector<ColumnSample> out(xy.size(), ColumnSample{nan, 0.0});
  if (grid.count() == 0) return out;
  with_kernel(kernel, [&](auto k) {
    using Kernel = decltype(k);
    Column column;
    for (std::size_t s = 0; s < xy.size(); ++s) {
      grid.gather(xy[s][0], xy[s][1], column);
      out[s] = {column_surface<Kernel>(column, rho_crit, vertical_step), column_density<Kernel>(column, 0.0)};
    }
  });
  return out;
}

std::string crater_json_text(const CraterMeasurement& m, double time) {
  using nlohmann::json;
  json radii = json::object();
  for (std::size_t d = 0; d < 4; ++d) radii[direction_names[d]] = m.radii[d];
  json ejected_by_material = json::object();
  for (const auto& [material, mass] : m.ejected_mass_by_material)
    ejected_by_material[std::to_string(material)] = mass;
  json j = {{"crater_radius", m.crater_radius},
            {"crater_radius_uncertainty", m.crater_radius_uncertainty},
            {"radius_spread", m.radius_spread},
            {"radii", radii},
            {"directions", directions_json(m)},
            {"mean_azimuthal_radius", m.mean_azimuthal_radius},
            {"outline", outline_json(m)},
            {"asymmetry",
             {{"min_edge_radius", m.min_edge_radius},
              {"min_edge_azimuth_deg", degrees(m.min_edge_azimuth)},
              {"max_edge_radius", m.max_edge_radius},
              {"max_edge_azimuth_deg", degrees(m.max_edge_azimuth)},
              {"centre_offset", {m.outline_centre_offset[0], m.outline_centre_offset[1]}}}},
            {"depth", m.depth},
            {"rim_height", m.rim_height},
            {"rim_radius", m.rim_radius},
            {"wall_slope_deg", m.wall_slope},
            {"volume", m.volume},
            {"ejected_mass", m.ejected_mass},
            {"ejected_particles", m.ejected_particles},
            {"ejected_mass_by_material", ejected_by_material},
            {"boulders", boulders_json(m)},
            {"warnings", m.warnings},
            {"settings", settings_json(m)}};
  if (std::isfinite(time)) j["time"] = time;
  return j.dump(2) + "\n";
}

std::string crater_profile_csv_text(const CraterMeasurement& m) {
  std::ostringstream out;
  out << "radius_m,mean_height_m,min_height_m,max_height_m,azimuths\n";
  for (const auto& s : m.profile) {
    out << format_number(s.radius) << ',' << format_number(s.mean_height) << ','
        << format_number(s.min_height) << ',' << format_number(s.max_height) << ',' << s.azimuths << '\n';
  }
  return out.str();
}

void write_crater_files(const std::filesystem::path& directory, const CraterMeasurement& m, double time) {
  if (!directory.empty()) std::filesystem::create_directories(directory);
  write_text_atomically(directory / "crater.json", crater_json_text(m, time));
  write_text_atomically(directory / "crater_profile.csv", crater_profile_csv_text(m));
}

}  // namespace craterkit::impact
