#pragma once
// Solid shapes for placing boulders in an impact target (docs/physics.md section 4; impact_setup.hpp).
// A Shape is the INTERSECTION of its parts: a point belongs to it when every part contains it. One part
// gives the primitive itself (a sphere); several parts give blocks such as docs/physics.md's boulder 4,
//   sqrt(x^2 + y^2) < 9, x < -2, |y| < 5, -5 < z < 0.5
//   = cylinder(axis (0, 0), radius 9) ∩ half-space(x < -2) ∩ box(y in (-5, 5), z in (-5, 0.5)).
// All inequalities are strict (a point on a boundary is outside), and all lengths are in m.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <variant>
#include <vector>

namespace craterkit::impact {

struct Sphere {
  std::array<double, 3> centre{0.0, 0.0, 0.0};
  double radius = 0.0;
};

// Infinite cylinder with a vertical (z) axis through (axis[0], axis[1]); bound it in z with half-spaces
// or a box in the same Shape.
struct VerticalCylinder {
  std::array<double, 2> axis{0.0, 0.0};
  double radius = 0.0;
};

// The points with normal . x < offset (normal need not be unit length; offset is in the same units).
struct HalfSpace {
  std::array<double, 3> normal{0.0, 0.0, 1.0};
  double offset = 0.0;
};

// Axis-aligned box lower < x < upper per axis (a bound may be infinite).
struct AxisAlignedBox {
  std::array<double, 3> lower{-std::numeric_limits<double>::infinity(),
                              -std::numeric_limits<double>::infinity(),
                              -std::numeric_limits<double>::infinity()};
  std::array<double, 3> upper{std::numeric_limits<double>::infinity(),
                              std::numeric_limits<double>::infinity(),
                              std::numeric_limits<double>::infinity()};
};

using ShapePart = std::variant<Sphere, VerticalCylinder, HalfSpace, AxisAlignedBox>;

// Intersection of its parts (an empty Shape contains nothing).
struct Shape {
  std::vector<ShapePart> parts;
};

[[nodiscard]] inline bool contains(const Sphere& s, double x, double y, double z) noexcept {
  const double dx = x - s.centre[0], dy = y - s.centre[1], dz = z - s.centre[2];
  return dx * dx + dy * dy + dz * dz < s.radius * s.radius;
}

[[nodiscard]] inline bool contains(const VerticalCylinder& c, double x, double y, double /*z*/) noexcept {
  const double dx = x - c.axis[0], dy = y - c.axis[1];
  return dx * dx + dy * dy < c.radius * c.radius;
}

[[nodiscard]] inline bool contains(const HalfSpace& h, double x, double y, double z) noexcept {
  return h.normal[0] * x + h.normal[1] * y + h.normal[2] * z < h.offset;
}

[[nodiscard]] inline bool contains(const AxisAlignedBox& b, double x, double y, double z) noexcept {
  return b.lower[0] < x && x < b.upper[0] && b.lower[1] < y && y < b.upper[1] && b.lower[2] < z &&
         z < b.upper[2];
}

[[nodiscard]] inline bool contains(const ShapePart& part, double x, double y, double z) noexcept {
  return std::visit([&](const auto& p) { return contains(p, x, y, z); }, part);
}

[[nodiscard]] inline bool contains(const Shape& shape, double x, double y, double z) noexcept {
  if (shape.parts.empty()) return false;
  for (const ShapePart& part : shape.parts) {
    if (!contains(part, x, y, z)) return false;
  }
  return true;
}

// The open interval (low, high) of heights z at which the vertical line through (x, y) lies inside the
// shape (every primitive is convex, so its section with a line is one interval, and so is their
// intersection); empty (low >= high) when the line misses it. Bounds may be infinite. Used to integrate
// the lithostatic pressure down a column through the boulders above a particle (impact_setup.cpp).
struct VerticalExtent {
  double low = -std::numeric_limits<double>::infinity();
  double high = std::numeric_limits<double>::infinity();
  [[nodiscard]] bool empty() const noexcept { return !(low < high); }
};

[[nodiscard]] inline VerticalExtent vertical_extent(const Sphere& s, double x, double y) noexcept {
  const double dx = x - s.centre[0], dy = y - s.centre[1];
  const double d2 = s.radius * s.radius - dx * dx - dy * dy;
  if (!(d2 > 0.0)) return {0.0, 0.0};
  const double half = std::sqrt(d2);
  return {s.centre[2] - half, s.centre[2] + half};
}

[[nodiscard]] inline VerticalExtent vertical_extent(const VerticalCylinder& c, double x, double y) noexcept {
  if (contains(c, x, y, 0.0)) return {};
  return {0.0, 0.0};
}

[[nodiscard]] inline VerticalExtent vertical_extent(const HalfSpace& h, double x, double y) noexcept {
  const double rest = h.offset - h.normal[0] * x - h.normal[1] * y;  // n_z z < rest
  if (h.normal[2] > 0.0) return {-std::numeric_limits<double>::infinity(), rest / h.normal[2]};
  if (h.normal[2] < 0.0) return {rest / h.normal[2], std::numeric_limits<double>::infinity()};
  if (rest > 0.0) return {};
  return {0.0, 0.0};
}

[[nodiscard]] inline VerticalExtent vertical_extent(const AxisAlignedBox& b, double x, double y) noexcept {
  if (b.lower[0] < x && x < b.upper[0] && b.lower[1] < y && y < b.upper[1]) return {b.lower[2], b.upper[2]};
  return {0.0, 0.0};
}

[[nodiscard]] inline VerticalExtent vertical_extent(const Shape& shape, double x, double y) noexcept {
  if (shape.parts.empty()) return {0.0, 0.0};
  VerticalExtent out;
  for (const ShapePart& part : shape.parts) {
    const VerticalExtent e = std::visit([&](const auto& p) { return vertical_extent(p, x, y); }, part);
    out.low = std::max(out.low, e.low);
    out.high = std::min(out.high, e.high);
  }
  return out;
}

}  // namespace craterkit::impact
