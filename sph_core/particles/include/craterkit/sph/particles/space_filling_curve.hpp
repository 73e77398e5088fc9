#pragma once
// Ordering particles along a Morton (Z-order) space-filling curve, so that particles near in space
// are near in memory: the neighbour search and the pair loops then touch few cache lines.
//
// Keys interleave 21 bits per axis (63 bits) of the position scaled into the bounding CUBE of the
// points (cubic, so a key prefix of 3k bits is an octree cell of level k; the octree neighbour search
// uses the same keys). Particles must have finite coordinates.
#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace craterkit::sph {

inline constexpr int morton_bits_per_axis = 21;

// Spreads the low 21 bits of v so that bit k moves to bit 3k.
[[nodiscard]] constexpr std::uint64_t spread_bits_3d(std::uint64_t v) noexcept {
  v &= 0x1fffffULL;
  v = (v | (v << 32)) & 0x1f00000000ffffULL;
  v = (v | (v << 16)) & 0x1f0000ff0000ffULL;
  v = (v | (v << 8)) & 0x100f00f00f00f00fULL;
  v = (v | (v << 4)) & 0x10c30c30c30c30c3ULL;
  v = (v | (v << 2)) & 0x1249249249249249ULL;
  return v;
}

// Morton key of integer cell coordinates (each < 2^21): x in bit 3k+2, y in 3k+1, z in 3k.
[[nodiscard]] constexpr std::uint64_t morton_key(std::uint32_t ix, std::uint32_t iy,
                                                 std::uint32_t iz) noexcept {
  return (spread_bits_3d(ix) << 2) | (spread_bits_3d(iy) << 1) | spread_bits_3d(iz);
}

// The cube the keys are computed over: lower corner and edge length (> 0).
struct CurveCube {
  std::array<double, 3> lower{0.0, 0.0, 0.0};
  double edge = 1.0;
};

// Morton key of a point within `cube` (points outside are clamped to its faces).
[[nodiscard]] inline std::uint64_t morton_key(const CurveCube& cube, double x, double y, double z) noexcept {
  constexpr double cells = double(1u << morton_bits_per_axis);
  const double inverse = cells / cube.edge;
  const auto cell = [inverse](double v, double lower) {
    return static_cast<std::uint32_t>(std::clamp((v - lower) * inverse, 0.0, cells - 1));
  };
  return morton_key(cell(x, cube.lower[0]), cell(y, cube.lower[1]), cell(z, cube.lower[2]));
}

// Smallest cube containing every point (slightly enlarged so the upper faces map inside the grid).
// OpenMP-parallel. Throws std::invalid_argument on mismatched spans or non-finite coordinates.
[[nodiscard]] CurveCube bounding_cube(std::span<const double> x, std::span<const double> y,
                                      std::span<const double> z);
// The cube bounding_cube gives for points whose extent is [lower, upper] (finite, lower <= upper): also for
// an extent reduced over the ranks of a distributed run (domain/curve_split.hpp), so that every rank's keys
// are those of one cube.
[[nodiscard]] CurveCube cube_around(const std::array<double, 3>& lower, const std::array<double, 3>& upper);

// Morton key of every point within `cube` (points outside are clamped to its faces). keys.size() == x.size().
void morton_keys(std::span<const double> x, std::span<const double> y, std::span<const double> z,
                 const CurveCube& cube, std::span<std::uint64_t> keys);

// Permutation that sorts the points along the curve over their bounding cube: new index k takes the
// point at old index order[k] (what Particles::permute expects). Ties keep the old index order, so the
// result is deterministic and independent of the thread count. `order` is resized and reused.
void curve_order(std::span<const double> x, std::span<const double> y, std::span<const double> z,
                 std::vector<std::uint32_t>& order);
[[nodiscard]] std::vector<std::uint32_t> curve_order(std::span<const double> x, std::span<const double> y,
                                                     std::span<const double> z);

// Sorts (key, index) pairs by key then index; OpenMP-parallel (parallel-mode sort) for large inputs.
void sort_keyed_indices(std::vector<std::pair<std::uint64_t, std::uint32_t>>& items);

}  // namespace craterkit::sph
