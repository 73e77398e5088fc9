// Morton keys and curve_order: bit interleaving by hand, permutation, locality, determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include "craterkit/sph/particles/space_filling_curve.hpp"

namespace craterkit::sph {
namespace {

TEST(SpaceFillingCurve, MortonKeyInterleavesBits) {
  // x goes to bit 3k+2, y to 3k+1, z to 3k.
  EXPECT_EQ(morton_key(1, 0, 0), 4u);
  EXPECT_EQ(morton_key(0, 1, 0), 2u);
  EXPECT_EQ(morton_key(0, 0, 1), 1u);
  EXPECT_EQ(morton_key(3, 0, 0), 0b100100u);
  EXPECT_EQ(morton_key(5, 6, 3), 0b110'011'101u);  // (x,y,z) bits at k=2: 1,1,0; k=1: 0,1,1; k=0: 1,0,1
  const std::uint32_t all = (1u << 21) - 1;
  EXPECT_EQ(morton_key(all, all, all), (std::uint64_t{1} << 63) - 1);
  EXPECT_EQ(morton_key(all, 0, 0), 0x4924924924924924ULL);
}

struct Lattice {
  std::vector<double> x, y, z;
};

// An m^3 lattice of unit spacing, listed in a random order.
Lattice shuffled_lattice(int m, unsigned seed) {
  std::vector<int> cells(m * m * m);
  std::iota(cells.begin(), cells.end(), 0);
  std::shuffle(cells.begin(), cells.end(), std::mt19937(seed));
  Lattice l;
  for (const int c : cells) {
    l.x.push_back(c % m);
    l.y.push_back((c / m) % m);
    l.z.push_back(c / (m * m));
  }
  return l;
}

double mean_step(const Lattice& l, const std::vector<std::uint32_t>& order) {
  double sum = 0;
  for (std::size_t k = 1; k < order.size(); ++k) {
    const std::uint32_t a = order[k - 1], b = order[k];
    sum +=
        std::sqrt(std::pow(l.x[a] - l.x[b], 2) + std::pow(l.y[a] - l.y[b], 2) + std::pow(l.z[a] - l.z[b], 2));
  }
  return sum / double(order.size() - 1);
}

TEST(SpaceFillingCurve, CurveOrderIsAPermutationThatPutsNearParticlesNear) {
  const int m = 16;
  const Lattice l = shuffled_lattice(m, 1);
  const std::vector<std::uint32_t> order = curve_order(l.x, l.y, l.z);
  ASSERT_EQ(order.size(), l.x.size());
  std::vector<std::uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t k = 0; k < sorted.size(); ++k) ASSERT_EQ(sorted[k], k);

  // Consecutive particles along the curve are about one spacing apart (a Z-curve jumps at block
  // boundaries, so the mean is a little above 1); in the shuffled order they are about 0.66 m apart.
  std::vector<std::uint32_t> identity(order.size());
  std::iota(identity.begin(), identity.end(), 0u);
  EXPECT_LT(mean_step(l, order), 2.0);
  EXPECT_GT(mean_step(l, identity), 0.5 * m);

  // Every aligned 2x2x2 block (and 4x4x4 block) of the lattice is a contiguous run of the order.
  for (const int block : {2, 4}) {
    for (std::size_t start = 0; start < order.size(); start += block * block * block) {
      const std::uint32_t first = order[start];
      const int bx = int(l.x[first]) / block, by = int(l.y[first]) / block, bz = int(l.z[first]) / block;
      for (int k = 0; k < block * block * block; ++k) {
        const std::uint32_t p = order[start + k];
        ASSERT_EQ(int(l.x[p]) / block, bx);
        ASSERT_EQ(int(l.y[p]) / block, by);
        ASSERT_EQ(int(l.z[p]) / block, bz);
      }
    }
  }
}

TEST(SpaceFillingCurve, LargeInputSortsKeysWithTiesInIndexOrder) {
  // Above 50 000 points the parallel sort is used: keys must come out non-decreasing, ties by index.
  std::mt19937_64 rng(2);
  std::uniform_int_distribution<int> cell(0, 40);  // few distinct positions: many equal keys
  std::vector<double> x, y, z;
  for (int i = 0; i < 120000; ++i) {
    x.push_back(cell(rng));
    y.push_back(cell(rng));
    z.push_back(cell(rng));
  }
  const std::vector<std::uint32_t> order = curve_order(x, y, z);
  std::vector<std::uint64_t> keys(x.size());
  morton_keys(x, y, z, bounding_cube(x, y, z), keys);
  ASSERT_EQ(order.size(), x.size());
  std::vector<bool> seen(x.size(), false);
  for (std::size_t k = 0; k < order.size(); ++k) {
    ASSERT_FALSE(seen[order[k]]);
    seen[order[k]] = true;
    if (k > 0) {
      const std::uint64_t a = keys[order[k - 1]], b = keys[order[k]];
      ASSERT_TRUE(a < b || (a == b && order[k - 1] < order[k])) << k;
    }
  }
}

TEST(SpaceFillingCurve, TiesKeepIndexOrderAndEmptyInputWorks) {
  const std::vector<double> x{1, 0, 1, 0}, y{0, 0, 0, 0}, z{0, 0, 0, 0};
  EXPECT_EQ(curve_order(x, y, z), (std::vector<std::uint32_t>{1, 3, 0, 2}));
  EXPECT_TRUE(curve_order({}, {}, {}).empty());
  const std::vector<double> one{5.0};
  EXPECT_EQ(curve_order(one, one, one), (std::vector<std::uint32_t>{0}));
}

TEST(SpaceFillingCurve, BoundingCubeContainsEveryPoint) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> normal(0.0, 10.0);
  std::vector<double> x, y, z;
  for (int i = 0; i < 1000; ++i) {
    x.push_back(normal(rng));
    y.push_back(2 * normal(rng));
    z.push_back(normal(rng) + 100);
  }
  const CurveCube cube = bounding_cube(x, y, z);
  for (int i = 0; i < 1000; ++i) {
    EXPECT_GE(x[i], cube.lower[0]);
    EXPECT_LT(x[i], cube.lower[0] + cube.edge);
    EXPECT_LT(y[i], cube.lower[1] + cube.edge);
    EXPECT_LT(z[i], cube.lower[2] + cube.edge);
  }
  std::vector<std::uint64_t> keys(x.size());
  morton_keys(x, y, z, cube, keys);
  EXPECT_LT(*std::max_element(keys.begin(), keys.end()), std::uint64_t{1} << 63);
  std::vector<double> bad = x;
  bad[3] = std::nan("");
  EXPECT_THROW((void)bounding_cube(bad, y, z), std::invalid_argument);
  EXPECT_THROW((void)curve_order(x, y, std::vector<double>(3)), std::invalid_argument);
}

}  // namespace
}  // namespace craterkit::sph
