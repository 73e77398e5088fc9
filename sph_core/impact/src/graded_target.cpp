// Graded-resolution target geometry (graded_target.hpp; docs/impact_setup.md "Graded resolution").
#include "craterkit/impact/graded_target.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>
#include <string>

#include "craterkit/sph/neighbours/neighbour_search.hpp"
#include "craterkit/sph/particles/kernel.hpp"

namespace craterkit::impact {

using namespace sph;

namespace {

constexpr double pi = std::numbers::pi;
// Junction smoothing: 10 iterations at 0.1 h^2 (test_graded_target.cpp: the largest h |sum V grad W| at
// the junction falls from 0.23-0.25 to 0.06; in the prototype it crept back up from the band's edges with
// more iterations: 0.052 after 10, 0.066 after 40).
constexpr int junction_smoothing_iterations = 10;
constexpr double junction_smoothing_coefficient = 0.1;

// The quadrant's core nodes (i, j, k >= 0) with r < R_c, calling f(x, y, z) by columns from the top down.
template <class F>
void for_each_core_node(const GradedSpacing& s, F&& f) {
  const double dx = s.inner_spacing, rc2 = s.inner_radius * s.inner_radius;
  const auto n = static_cast<long>(std::ceil(s.inner_radius / dx)) + 1;
  for (long i = 0; i < n; ++i) {
    const double x = (static_cast<double>(i) + 0.5) * dx;
    for (long j = 0; j < n; ++j) {
      const double y = (static_cast<double>(j) + 0.5) * dx;
      for (long k = 0; k < n; ++k) {
        const double z = -(static_cast<double>(k) + 0.5) * dx;
        if (x * x + y * y + z * z < rc2) f(x, y, z);
      }
    }
  }
}

struct Ring {
  double u = 0.0;   // cos(theta) = -z/r at the ring
  double du = 0.0;  // band height in u
  long points = 0;  // N, a multiple of 4
  bool top = false;
};

// The rings of one shell from the bottom (the pole, u = 1) up to the top band 0 < u < t/r.
//  - Polar cap: four cells of area t^2 (at radius r), 1 - u < 2 t^2 / (pi r^2), their points at t/sqrt(2)
//    from the axis at azimuths 45 deg + k 90 deg: a 2 x 2 lattice column of spacing t around the axis.
//    (Tried in a prototype, docs/impact_setup.md: a cap one spacing high with its points at the band's
//    middle leaves cells of 0.785 t^2 and neighbour numbers down to 0.81 of the lattice's; cells of t^2
//    everywhere, band heights adapted to N, leave a hole on the axis, h |sum V grad W| = 0.2.)
//  - Then bands of equal width in theta up to acos(t/r), about one spacing each, points at the middle of
//    the band in u (which halves its area) and N = 4 max(1, round(A / (4 t^2))) per ring;
//  - the top band 0 < u < t/r, its ring at z = -t/2.
template <class F>
void for_each_ring(const GradedShell& shell, F&& f) {
  const double r = shell.centre(), t = shell.thickness();
  const double u_top = t / r;
  const double theta_top = std::acos(u_top);
  const double u_cap = 1.0 - 2.0 * t * t / (pi * r * r);
  const double theta_cap = std::acos(u_cap);
  const long bands = std::max(1L, std::lround((theta_top - theta_cap) * r / t));
  Ring cap;
  cap.u = std::sqrt(1.0 - 0.5 * u_top * u_top);
  cap.du = 1.0 - u_cap;
  cap.points = 4;
  f(cap);
  // Band edges in u from the cap down to the top band's lower edge u_top, then 0; the band heights
  // telescope to exactly 1, so the cells of one shell tile it.
  double upper = u_cap;
  for (long e = 1; e <= bands + 1; ++e) {
    const double lower = e < bands ? std::cos(theta_cap + (theta_top - theta_cap) * static_cast<double>(e) /
                                                              static_cast<double>(bands))
                                   : (e == bands ? u_top : 0.0);
    const double du = upper - lower;
    Ring ring;
    ring.top = e == bands + 1;
    ring.u = 0.5 * (upper + lower);
    ring.du = du;
    ring.points = 4 * std::max(1L, std::lround(2.0 * pi * r * r * du / (4.0 * t * t)));
    f(ring);
    upper = lower;
  }
}

// Junction smoothing (graded_target.hpp): particle shifting (Xu, Stansby & Laurence 2009; Lind et al.
// 2012) of the points within [R_c - 3 dx0, R_c + 4 dx0], delta x_i = -0.1 h_i^2 sum_j V_j grad_i W_ij (the
// gradient of the kernel sum, cubic spline at the mean h), Jacobi iterations, horizontal only where the
// kernel support reaches the free surface (-z < 2.5 h: there the sum's gradient is the surface's). The sums
// run over the quadrant and its three mirror images, so the shifted set keeps both mirror symmetries
// exactly and does not depend on the symmetry of the run.
void smooth_junction(std::vector<GradedPoint>& q, const GradedLayout& layout, double eta) {
  const double dx0 = layout.spacing.inner_spacing, rc = layout.spacing.inner_radius;
  const double band_low = rc - 3.0 * dx0, band_high = rc + 4.0 * dx0;
  // Every neighbour of a band point lies within r < band_high + 2 (h_i + h_j); the shells there are at
  // most a few dx0 thick, so 12 dx0 is ample.
  const double reach = band_high + 12.0 * dx0;
  std::vector<std::size_t> near;
  for (std::size_t i = 0; i < q.size(); ++i) {
    if (std::hypot(q[i].x, q[i].y, q[i].z) < reach) near.push_back(i);
  }
  const std::size_t n = near.size();
  std::vector<double> x(4 * n), y(4 * n), z(4 * n), h(4 * n), volume(4 * n);
  std::vector<std::array<double, 3>> shift(n);
  NeighbourSearch search;
  NeighbourLists lists;
  for (int iteration = 0; iteration < junction_smoothing_iterations; ++iteration) {
    for (std::size_t a = 0; a < n; ++a) {
      const GradedPoint& p = q[near[a]];
      const double sx[4] = {1.0, -1.0, 1.0, -1.0}, sy[4] = {1.0, 1.0, -1.0, -1.0};
      for (std::size_t m = 0; m < 4; ++m) {
        x[4 * a + m] = sx[m] * p.x;
        y[4 * a + m] = sy[m] * p.y;
        z[4 * a + m] = p.z;
        h[4 * a + m] = eta * std::cbrt(p.volume);
        volume[4 * a + m] = p.volume;
      }
    }
    search.build({x, y, z, h}, Box{}, lists);
    for (std::size_t a = 0; a < n; ++a) {
      shift[a] = {0.0, 0.0, 0.0};
      const std::size_t i = 4 * a;  // the quadrant's own image
      const double r = std::hypot(x[i], y[i], z[i]);
      if (r < band_low || r > band_high) continue;
      double g[3] = {0.0, 0.0, 0.0};
      for (const std::uint32_t j : lists.of(i)) {
        const double d[3] = {x[i] - x[j], y[i] - y[j], z[i] - z[j]};
        const double distance = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        const double w = volume[j] * CubicSpline::derivative(distance, 0.5 * (h[i] + h[j])) / distance;
        for (int c = 0; c < 3; ++c) g[c] += w * d[c];
      }
      const double k = -junction_smoothing_coefficient * h[i] * h[i];
      shift[a] = {k * g[0], k * g[1], -z[i] < 2.5 * h[i] ? 0.0 : k * g[2]};
    }
    for (std::size_t a = 0; a < n; ++a) {
      GradedPoint& p = q[near[a]];
      p.x += shift[a][0];
      p.y += shift[a][1];
      p.z += shift[a][2];
    }
  }
}

}  // namespace

GradedLayout graded_layout(const GradedSpacing& spacing, double domain_radius) {
  if (!spacing.graded()) throw std::invalid_argument("graded_layout: the spacing is not graded");
  const double dx0 = spacing.inner_spacing, dx_max = spacing.outer_spacing, R = domain_radius;
  if (!(spacing.inner_radius >= 4.0 * dx0 * (1.0 - 1e-12)) || !(spacing.inner_radius < R - 4.0 * dx_max)) {
    throw std::invalid_argument("graded_layout: the core radius must lie in [4 dx0, R_dom - 4 dx_max)");
  }
  GradedLayout out;
  out.spacing = spacing;
  out.domain_radius = R;
  std::size_t quadrant = 0;
  for_each_core_node(spacing, [&](double, double, double) { ++quadrant; });
  out.core_cells = 4 * quadrant;
  out.core_radius = std::cbrt(3.0 * static_cast<double>(out.core_cells) * dx0 * dx0 * dx0 / (2.0 * pi));

  // Thicknesses by the growth rule until the shells pass R_dom.
  std::vector<double> thickness;
  double edge = out.core_radius, t = dx0;
  // Beyond the far radius the cap is the far spacing: the shells grow again, by the same rule.
  const bool coarsened = spacing.coarsened();
  if (coarsened && !(spacing.far_radius >= spacing.outer_radius() && spacing.far_radius < R)) {
    throw std::invalid_argument("graded_layout: the far radius must lie in [" +
                                std::to_string(spacing.outer_radius()) +
                                " m (where the shells reach dx_max), R_dom)");
  }
  while (edge < R) {
    thickness.push_back(t);
    edge += t;
    t = std::min(coarsened && edge >= spacing.far_radius ? spacing.far_spacing : dx_max,
                 t * (1.0 + spacing.grading));
  }
  // The shell count whose outer edge lies closest to R_dom (the last shell dropped when that is closer).
  const double length = R - out.core_radius;
  const double with_last = edge - out.core_radius, without_last = with_last - thickness.back();
  if (thickness.size() > 1 && std::abs(without_last - length) < std::abs(with_last - length)) {
    thickness.pop_back();
  }
  double total = 0.0;
  for (const double d : thickness) total += d;
  out.thickness_scale = length / total;
  edge = out.core_radius;
  for (std::size_t k = 0; k < thickness.size(); ++k) {
    GradedShell shell;
    shell.inner = edge;
    shell.outer = k + 1 == thickness.size() ? R : edge + out.thickness_scale * thickness[k];
    edge = shell.outer;
    out.shells.push_back(shell);
    if (thickness[k] < dx_max) out.graded_shells = k + 1;
    if (thickness[k] > dx_max && out.coarse_shells == 0) out.coarse_shells = thickness.size() - k;
    // The polar cap and the top band must fit (u_cap > u_top): true for r >= 3 t, which R_c >= 4 dx0
    // guarantees as long as the spacing grows no faster than the radius (s <= 0.2).
    if (shell.centre() < 3.0 * shell.thickness()) {
      throw std::invalid_argument("graded_layout: shell " + std::to_string(k) +
                                  " at r = " + std::to_string(shell.centre()) +
                                  " m is thinner than a third of its radius");
    }
  }
  return out;
}

std::vector<GradedPoint> graded_quadrant_points(const GradedLayout& layout, double eta) {
  std::vector<GradedPoint> out;
  out.reserve(graded_point_count(layout) / 4);
  const double dx0 = layout.spacing.inner_spacing, cell = dx0 * dx0 * dx0;
  for_each_core_node(layout.spacing, [&](double x, double y, double z) {
    out.push_back({x, y, z, cell, dx0, -1, z == -0.5 * dx0});
  });
  for (std::size_t k = 0; k < layout.shells.size(); ++k) {
    const GradedShell& shell = layout.shells[k];
    const double r = shell.centre(), t = shell.thickness();
    const double radial =
        (shell.outer * shell.outer * shell.outer - shell.inner * shell.inner * shell.inner) / 3.0;
    for_each_ring(shell, [&](const Ring& ring) {
      // The top ring exactly at z = -t/2 (r u = t/2 only up to rounding otherwise).
      const double z = ring.top ? -0.5 * t : -r * ring.u;
      const double rho = std::sqrt(r * r - z * z);
      const double sector = 2.0 * pi / static_cast<double>(ring.points);
      const double volume = radial * ring.du * sector;
      for (long m = 0; m < ring.points / 4; ++m) {
        const double phi = (static_cast<double>(m) + 0.5) * sector;
        out.push_back(
            {rho * std::cos(phi), rho * std::sin(phi), z, volume, t, static_cast<int>(k), ring.top});
      }
    });
  }
  if (eta > 0.0) smooth_junction(out, layout, eta);
  return out;
}

std::size_t graded_point_count(const GradedLayout& layout) {
  std::size_t n = layout.core_cells;
  for (const GradedShell& shell : layout.shells) {
    for_each_ring(shell, [&](const Ring& ring) { n += static_cast<std::size_t>(ring.points); });
  }
  return n;
}

}  // namespace craterkit::impact
