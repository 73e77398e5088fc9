#include "craterkit/sph/particles/space_filling_curve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#if __has_include(<parallel/algorithm>)  // libstdc++ parallel mode (OpenMP); plain std::sort otherwise
#include <parallel/algorithm>
#define CRATERKIT_GNU_PARALLEL_SORT 1
#endif

namespace craterkit::sph {

namespace {

void check_sizes(std::span<const double> x, std::span<const double> y, std::span<const double> z) {
  if (y.size() != x.size() || z.size() != x.size()) {
    throw std::invalid_argument("space-filling curve: x, y and z must have the same length");
  }
  if (x.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("space-filling curve: more than 2^32-1 points");
  }
}

}  // namespace

CurveCube bounding_cube(std::span<const double> x, std::span<const double> y, std::span<const double> z) {
  check_sizes(x, y, z);
  const std::size_t n = x.size();
  if (n == 0) return {};
  constexpr double inf = std::numeric_limits<double>::infinity();
  double lo0 = inf, lo1 = inf, lo2 = inf, hi0 = -inf, hi1 = -inf, hi2 = -inf;
  bool finite = true;
#pragma omp parallel for schedule(static) reduction(min : lo0, lo1, lo2) reduction(max : hi0, hi1, hi2) \
    reduction(&& : finite)
  for (std::size_t i = 0; i < n; ++i) {
    finite = finite && std::isfinite(x[i]) && std::isfinite(y[i]) && std::isfinite(z[i]);
    lo0 = std::min(lo0, x[i]);
    hi0 = std::max(hi0, x[i]);
    lo1 = std::min(lo1, y[i]);
    hi1 = std::max(hi1, y[i]);
    lo2 = std::min(lo2, z[i]);
    hi2 = std::max(hi2, z[i]);
  }
  if (!finite) throw std::invalid_argument("space-filling curve: non-finite particle coordinate");
  return cube_around({lo0, lo1, lo2}, {hi0, hi1, hi2});
}

CurveCube cube_around(const std::array<double, 3>& lower, const std::array<double, 3>& upper) {
  double edge = std::max({upper[0] - lower[0], upper[1] - lower[1], upper[2] - lower[2]});
  const double scale = std::max({std::abs(lower[0]), std::abs(lower[1]), std::abs(lower[2]),
                                 std::abs(upper[0]), std::abs(upper[1]), std::abs(upper[2]), edge});
  // Enlarge a little so that the upper faces map to the last cell, not one past it; a zero extent
  // (all points equal) gets a unit-relative edge.
  edge = edge > 0 ? edge * (1 + 1e-9) : (scale > 0 ? scale * 1e-9 : 1.0);
  return {lower, edge};
}

void morton_keys(std::span<const double> x, std::span<const double> y, std::span<const double> z,
                 const CurveCube& cube, std::span<std::uint64_t> keys) {
  check_sizes(x, y, z);
  if (keys.size() != x.size()) throw std::invalid_argument("morton_keys: keys must have one entry per point");
  const std::size_t n = x.size();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) keys[i] = morton_key(cube, x[i], y[i], z[i]);
}

void sort_keyed_indices(std::vector<std::pair<std::uint64_t, std::uint32_t>>& items) {
  // Nearly sorted input (particles re-sorted every few steps) is common: check first, it is O(n).
  if (std::is_sorted(items.begin(), items.end())) return;
#ifdef CRATERKIT_GNU_PARALLEL_SORT
  if (items.size() > 50000) {
    __gnu_parallel::sort(items.begin(), items.end());
    return;
  }
#endif
  std::sort(items.begin(), items.end());
}

void curve_order(std::span<const double> x, std::span<const double> y, std::span<const double> z,
                 std::vector<std::uint32_t>& order) {
  const CurveCube cube = bounding_cube(x, y, z);
  const std::size_t n = x.size();
  std::vector<std::pair<std::uint64_t, std::uint32_t>> items(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) items[i] = {morton_key(cube, x[i], y[i], z[i]), std::uint32_t(i)};
  sort_keyed_indices(items);
  order.resize(n);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) order[i] = items[i].second;
}

std::vector<std::uint32_t> curve_order(std::span<const double> x, std::span<const double> y,
                                       std::span<const double> z) {
  std::vector<std::uint32_t> order;
  curve_order(x, y, z, order);
  return order;
}

}  // namespace craterkit::sph
