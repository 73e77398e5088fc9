#pragma once
// Solid shapes for placing boulders in an impact target (physics.md section 4; impact_setup.hpp).
// A Shape is the INTERSECTION of its parts: a point belongs to it when every part contains it. One part
// gives the primitive itself (a sphere); several parts give blocks such as physics.md's boulder 4,
//   sqrt(x^2 + y^2) < 9, x < -2, |y| < 5, -5 < z < 0.5
//   = cylinder(axis (0, 0), radius 9) ∩ half-space(x < -2) ∩ box(y in (-5, 5), z in (-5, 0.5)).
// All inequalities are strict (a point on a boundary is outside), and all lengths are in m.
#include <array>
#include <cmath>
#include <limits>
#include <variant>
#include <vector>

namespace craterkit::sph {

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

}  // namespace craterkit::sph
