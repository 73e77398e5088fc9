#pragma once
// Geometry of a graded-resolution impact target (docs/physics.md section 4: "refine the particles near the
// impact point"; docs/impact_setup.md "Graded resolution"). Pure geometry: positions, cell volumes and
// local spacings; make_impact() (impact_setup.hpp) gives them materials, masses and the lithostatic state.
//
// z up, impact point at the origin, free surface z = 0; r the distance from the impact point.
//  - Core: the nodes ((i + 1/2) dx0, (j + 1/2) dx0, -(k + 1/2) dx0) of the cubic lattice with r < R_c, each
//    standing for its cell dx0^3 (the uniform target's lattice at the inner spacing: top layer at -dx0/2).
//  - Shells: hemispherical shells (below z = 0) around the impact point, starting at the core radius
//    rho_0, the radius of the hemisphere whose volume is that of the core cells (so that the volumes tile
//    the hemisphere exactly; the cubic core's boundary is a staircase within sqrt(3)/2 dx0 of r = R_c).
//    Thicknesses dx_0 = dx0, dx_{k+1} = min(dx_max, dx_k (1 + s)), then dx_max out to R_dom (with the far
//    coarsening, from the first shell starting at or beyond r_f: dx_{k+1} = min(dx_far, dx_k (1 + s))); all
//    of them are multiplied by one common factor f (the one closest to 1 over the possible shell counts) so
//    that the last shell ends exactly at R_dom (|f - 1| <= dx_max / (2 (R_dom - rho_0))).
//  - Rings: on a shell of centre radius r and thickness t, with u = cos(theta) = -z/r (theta the polar
//    angle from the downward vertical):
//      polar cap: four cells of area t^2, 1 - u < 2 t^2 / (pi r^2), their points t/sqrt(2) from the axis
//        (a 2 x 2 lattice column of spacing t around the axis below the impact point);
//      top band 0 < u < t/r: at radius r it spans -t < z < 0, and its ring lies at z = -t/2 exactly, so the
//        free surface is flat and the top layer lies half a local spacing below z = 0 everywhere, as on the
//        uniform lattice (docs/physics.md section 4; the crater measurement's rho_initial/2 convention);
//      in between, n = round(r (theta_top - theta_cap) / t) bands of equal width in theta (arc ~ t), each
//        ring at the middle of its band in u, which halves the band's area (Archimedes: a spherical zone's
//        area is proportional to its height), with N = 4 max(1, round(A / (4 t^2))) points (A the zone
//        area 2 pi r^2 du at radius r), so that every cell has an area close to t^2: the cells are close
//        to cubes of edge t.
//  - Azimuths (m + 1/2) 2 pi / N, N a multiple of 4: the set is exactly symmetric under x -> -x and
//    y -> -y (built by sign flips of the quadrant's points), no point lies on the planes x = 0 or y = 0,
//    and the quadrant x > 0, y > 0 is exactly a quarter of the full set (mirror planes on a quarter domain).
//    Rotating alternate rings by half a point spacing (to stagger them) is not possible under that
//    symmetry: any rotation other than these half offsets either puts points on a mirror plane or leaves
//    pairs of mirror images closer than one spacing across it. Rings of different N are staggered anyway;
//    consecutive rings with equal N (near the free surface) stand in columns as a cubic lattice does.
//  - Volumes: the cell of a ring point is its band x shell x azimuthal sector,
//    V = (r_out^3 - r_in^3)/3 du 2 pi / N: the cells tile the hemisphere.
//  - Junction smoothing: the cubic core's staircase boundary against the first spherical shell is where
//    the arrangement is least regular (pairs 0.63 dx0 apart, zeroth-order kernel-gradient error
//    h |sum_j V_j grad W_ij| up to 0.23-0.25, against <= 0.08 inside the shells). The points within
//    R_c - 3 dx0 < r < R_c + 4 dx0 are therefore moved by 10 iterations of particle shifting down the
//    gradient of the kernel sum (graded_target.cpp), by at most 0.14 dx0, which brings the error there to
//    0.06 and the closest pairs to 0.73 dx0 (test_graded_target.cpp). Volumes stay those of the cells.
//  - Above z = 0: the mirror image (x, y, -z) of every point, with the same cell, for the parts of
//    boulders that stick out of the surface (impact_setup.hpp).
#include <cstddef>
#include <vector>

#include "craterkit/impact/graded_spacing.hpp"

namespace craterkit::impact {

struct GradedShell {
  double inner = 0.0, outer = 0.0;  // radii, m
  [[nodiscard]] double centre() const noexcept { return 0.5 * (inner + outer); }
  [[nodiscard]] double thickness() const noexcept { return outer - inner; }
};

struct GradedLayout {
  GradedSpacing spacing;
  double domain_radius = 0.0;
  double core_radius = 0.0;    // rho_0, m: (2/3) pi rho_0^3 = core_cells dx0^3
  std::size_t core_cells = 0;  // core nodes below z = 0 in the full hemisphere
  std::vector<GradedShell> shells;
  std::size_t graded_shells = 0;  // shells before the first one at the outer spacing
  std::size_t coarse_shells = 0;  // the last shells, thicker than the outer spacing (spacing.coarsened())
  double thickness_scale = 1.0;   // f
};

// Throws std::invalid_argument unless spacing.graded() and 4 dx0 <= R_c < R_dom - 4 dx_max, and, with the
// far coarsening, spacing.outer_radius() <= r_f < R_dom.
GradedLayout graded_layout(const GradedSpacing& spacing, double domain_radius);

struct GradedPoint {
  double x = 0.0, y = 0.0, z = 0.0;  // m; x > 0, y > 0, z < 0
  double volume = 0.0;               // m^3, the point's cell
  double spacing = 0.0;              // m, local spacing: dx0 in the core, the shell's thickness outside
  int shell = -1;                    // -1: core; else the shell index
  bool top = false;                  // in the top layer (z = -spacing / 2)
};

// The points of the quadrant x > 0, y > 0 below z = 0, in a fixed order: the core by columns (x, y) from
// the top down, then the shells outward, each from the bottom ring up, azimuths increasing. eta > 0: the
// junction is smoothed with h = eta V^(1/3); eta = 0: the unsmoothed construction.
std::vector<GradedPoint> graded_quadrant_points(const GradedLayout& layout, double eta);

// The number of points in the full hemisphere below z = 0 (4 x the quadrant's), without building them.
std::size_t graded_point_count(const GradedLayout& layout);

}  // namespace craterkit::impact
