// Neighbour search with mirror planes (mirror_image.hpp): the lists of every real particle equal, as sets
// of (index, image bits) entries, a brute-force search against the real particles and their explicit
// reflections; the lists are symmetric in the mirrored sense, independent of the thread count, and the
// rebuild criterion stays sufficient; bad boxes are rejected.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "craterkit/sph/neighbours/neighbour_search.hpp"
#include "craterkit/sph/particles/mirror_image.hpp"

namespace craterkit::sph {
namespace {

struct Cloud {
  std::vector<double> x, y, z, h;
  [[nodiscard]] NeighbourInput input() const { return {x, y, z, h}; }
};

// n points uniform in lower + [0, 1)^3 with h in [h_lo, h_hi].
Cloud random_cloud(std::size_t n, const std::array<double, 3>& lower, double h_lo, double h_hi,
                   unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Cloud c;
  for (std::size_t i = 0; i < n; ++i) {
    c.x.push_back(lower[0] + unit(rng));
    c.y.push_back(lower[1] + unit(rng));
    c.z.push_back(lower[2] + unit(rng));
    c.h.push_back(h_lo + (h_hi - h_lo) * unit(rng));
  }
  return c;
}

Box mirror_box(const std::array<double, 3>& lower, const std::array<bool, 3>& mirror,
               const std::array<bool, 3>& periodic = {false, false, false}) {
  Box box;
  box.lower = lower;
  box.upper = {lower[0] + 1.0, lower[1] + 1.0, lower[2] + 1.0};
  box.periodic = periodic;
  box.mirror = mirror;
  return box;
}

// Reference written out independently of the library: every particle j and every explicit reflection of
// it across a subset of the mirrored axes (x_a -> 2 lower_a - x_a), minimum image by rounding on periodic
// axes; the entry is j | bits << 29. Only the identical entry (i itself, no reflection) is left out.
std::vector<std::vector<std::uint32_t>> brute_force(const Cloud& c, const Box& box, double skin) {
  const std::size_t n = c.x.size();
  std::vector<std::vector<std::uint32_t>> lists(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      for (unsigned bits = 0; bits < 8; ++bits) {
        bool allowed = true;
        for (int a = 0; a < 3; ++a) allowed = allowed && (!((bits >> a) & 1u) || box.mirror[a]);
        if (!allowed || (i == j && bits == 0)) continue;
        const double pj[3] = {c.x[j], c.y[j], c.z[j]};
        const double pi[3] = {c.x[i], c.y[i], c.z[i]};
        double d2 = 0.0;
        for (int a = 0; a < 3; ++a) {
          const double image = ((bits >> a) & 1u) ? 2.0 * box.lower[a] - pj[a] : pj[a];
          double d = pi[a] - image;
          if (box.periodic[a]) {
            const double edge = box.upper[a] - box.lower[a];
            d -= edge * std::round(d / edge);
          }
          d2 += d * d;
        }
        const double reach = (1 + skin) * (c.h[i] + c.h[j]);
        if (d2 < reach * reach) lists[i].push_back(std::uint32_t(j) | (bits << 29));
      }
    }
    std::sort(lists[i].begin(), lists[i].end());
  }
  return lists;
}

// Returns the number of image entries, so that a test can check that images were exercised.
std::size_t expect_equal_to_brute_force(const NeighbourLists& lists,
                                        const std::vector<std::vector<std::uint32_t>>& ref) {
  EXPECT_EQ(lists.particle_count(), ref.size());  // lists for the real particles only
  if (lists.particle_count() != ref.size()) return 0;
  std::size_t total = 0, images = 0;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    auto got = std::vector<std::uint32_t>(lists.of(i).begin(), lists.of(i).end());
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, ref[i]) << "particle " << i;
    if (got != ref[i]) return images;
    total += ref[i].size();
    for (const auto e : ref[i]) images += mirror_bits(e) != 0 ? 1 : 0;
  }
  EXPECT_EQ(lists.total(), total);
  return images;
}

struct Case {
  double skin;
  std::size_t leaf_size;
};

class MirrorSearchTest : public ::testing::TestWithParam<Case> {};

TEST_P(MirrorSearchTest, QuarterDomainEqualsBruteForceWithExplicitReflections) {
  // x > 0, y > 0 with planes x = 0 and y = 0 (the impact's quarter); h varies by a factor 3.
  const Cloud c = random_cloud(2500, {0, 0, 0}, 0.03, 0.09, 11);
  const Box box = mirror_box({0, 0, 0}, {true, true, false});
  NeighbourSearch search({GetParam().skin, GetParam().leaf_size});
  const NeighbourLists lists = search.build(c.input(), box);
  const std::size_t images = expect_equal_to_brute_force(lists, brute_force(c, box, GetParam().skin));
  EXPECT_GT(lists.mean_neighbours(), 10.0);
  EXPECT_GT(images, 2000u);  // image pairs (single and corner) are really exercised
  // Some particle near the corner lists its own corner image, and some its own x image.
  bool own_corner = false, own_x = false;
  for (std::size_t i = 0; i < lists.particle_count(); ++i) {
    for (const auto e : lists.of(i)) {
      own_corner = own_corner || e == neighbour_entry(std::uint32_t(i), 3u);
      own_x = own_x || e == neighbour_entry(std::uint32_t(i), 1u);
    }
  }
  EXPECT_TRUE(own_corner);
  EXPECT_TRUE(own_x);
}

TEST_P(MirrorSearchTest, PlanesOffTheOriginThreeAxesAndPeriodicMix) {
  const Cloud c = random_cloud(2000, {-0.4, 0.25, 3.0}, 0.02, 0.07, 12);
  for (const auto& [mirror, periodic] :
       {std::pair{std::array<bool, 3>{true, false, false}, std::array<bool, 3>{false, false, false}},
        std::pair{std::array<bool, 3>{true, true, true}, std::array<bool, 3>{false, false, false}},
        std::pair{std::array<bool, 3>{false, true, false}, std::array<bool, 3>{true, false, true}}}) {
    const Box box = mirror_box({-0.4, 0.25, 3.0}, mirror, periodic);
    SCOPED_TRACE(::testing::Message() << "mirror " << mirror[0] << mirror[1] << mirror[2] << " periodic "
                                      << periodic[0] << periodic[1] << periodic[2]);
    NeighbourSearch search({GetParam().skin, GetParam().leaf_size});
    EXPECT_GT(expect_equal_to_brute_force(search.build(c.input(), box), brute_force(c, box, GetParam().skin)),
              100u);
  }
}

TEST_P(MirrorSearchTest, ParticlesThatCrossedAPlaneAreStillExact) {
  // A few particles a little on the wrong side (x < 0): images of particles farther from the plane than
  // the usual reach then come within reach of them; the search must widen its band by that depth.
  Cloud c = random_cloud(2000, {0, 0, 0}, 0.03, 0.06, 13);
  for (std::size_t i = 0; i < c.x.size(); i += 97) c.x[i] = -0.05 * c.x[i];
  c.y[5] = -0.08;
  const Box box = mirror_box({0, 0, 0}, {true, true, false});
  NeighbourSearch search({GetParam().skin, GetParam().leaf_size});
  expect_equal_to_brute_force(search.build(c.input(), box), brute_force(c, box, GetParam().skin));
}

TEST_P(MirrorSearchTest, ListsAreSymmetricUnderReflection) {
  // image_A(j) in list(i) iff image_A(i) in list(j): a reflection preserves distances.
  const Cloud c = random_cloud(4000, {0, 0, 0}, 0.01, 0.05, 14);
  const Box box = mirror_box({0, 0, 0}, {true, true, false});
  NeighbourSearch search({GetParam().skin, GetParam().leaf_size});
  const NeighbourLists lists = search.build(c.input(), box);
  for (std::size_t i = 0; i < lists.particle_count(); ++i) {
    for (const std::uint32_t e : lists.of(i)) {
      const auto back = lists.of(neighbour_index(e));
      const std::uint32_t mirrored = neighbour_entry(std::uint32_t(i), mirror_bits(e));
      ASSERT_NE(std::find(back.begin(), back.end(), mirrored), back.end()) << i << " -> " << e;
    }
  }
}

TEST_P(MirrorSearchTest, IndependentOfThreadCountAndReusesBuffers) {
  const Cloud c = random_cloud(20000, {0, 0, 0}, 0.01, 0.03, 15);
  const Box box = mirror_box({0, 0, 0}, {true, true, false});
  NeighbourSearch search({GetParam().skin, GetParam().leaf_size});
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  NeighbourLists one;
  search.build(c.input(), box, one);
  // Steady state: a rebuild allocates nothing more (on one thread; with more, the per-thread scratch
  // follows the dynamic schedule until each thread has seen its largest group).
  const std::size_t bytes = search.workspace_bytes(), list_bytes = one.bytes();
  search.build(c.input(), box, one);
  EXPECT_EQ(search.workspace_bytes(), bytes);
  EXPECT_EQ(one.bytes(), list_bytes);
  omp_set_num_threads(2);
  NeighbourLists two;
  search.build(c.input(), box, two);
  search.build(c.input(), box, two);
  search.release_workspace();
  EXPECT_FALSE(search.needs_rebuild(c.input()));  // the build state (with the images) survives the release
  NeighbourLists three;
  search.build(c.input(), box, three);
  omp_set_num_threads(threads);
  EXPECT_EQ(one.offsets, two.offsets);
  EXPECT_EQ(one.neighbours, two.neighbours);  // the same order too
  EXPECT_EQ(one.neighbours, three.neighbours);
}

INSTANTIATE_TEST_SUITE_P(SkinAndLeafSize, MirrorSearchTest,
                         ::testing::Values(Case{0.0, 4}, Case{0.15, 16}, Case{0.0, 64}, Case{0.15, 64}));

TEST(MirrorSearch, RebuildCriterionIsSufficientWithImages) {
  // As for open boxes (test_neighbour_search.cpp), with the truth counted against the reflections: as long
  // as needs_rebuild() says no, the old lists hold every image pair of the moved particles too, also for
  // particles that were outside the image band at the build and moved towards a plane.
  const double skin = 0.2;
  const Cloud c = random_cloud(3000, {0, 0, 0}, 0.02, 0.05, 16);
  const Box box = mirror_box({0, 0, 0}, {true, true, false});
  NeighbourSearch search({skin, 16});
  const NeighbourLists lists = search.build(c.input(), box);
  EXPECT_FALSE(search.needs_rebuild(c.input()));
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int kept = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const double amplitude = 0.001 * (trial + 1);
    Cloud moved = c;
    for (std::size_t i = 0; i < c.x.size(); ++i) {
      // Towards both planes (the worst case for the image band), with a random part.
      moved.x[i] -= amplitude * (0.5 + 0.5 * unit(rng)) / std::sqrt(3.0);
      moved.y[i] -= amplitude * (0.5 + 0.5 * unit(rng)) / std::sqrt(3.0);
      moved.z[i] += amplitude * unit(rng) / std::sqrt(3.0);
      moved.h[i] *= 1.0 + 0.25 * amplitude * (unit(rng) + 1.0);
    }
    if (search.needs_rebuild(moved.input())) continue;
    ++kept;
    const auto truth = brute_force(moved, box, 0.0);
    for (std::size_t i = 0; i < truth.size(); ++i) {
      const auto have = lists.of(i);
      for (const std::uint32_t e : truth[i]) {
        ASSERT_NE(std::find(have.begin(), have.end(), e), have.end()) << "trial " << trial << " " << i;
      }
    }
  }
  EXPECT_GE(kept, 1);
  EXPECT_LT(kept, 12);
}

TEST(MirrorSearch, RejectsPeriodicMirrorAxesAndNonFinitePlanes) {
  NeighbourSearch search;
  const Cloud c{{0.1, 0.6}, {0.1, 0.2}, {0.1, 0.3}, {0.1, 0.1}};
  EXPECT_THROW(
      (void)search.build(c.input(), mirror_box({0, 0, 0}, {true, false, false}, {true, false, false})),
      std::invalid_argument);
  Box infinite = mirror_box({0, 0, 0}, {false, true, false});
  infinite.lower[1] = -std::numeric_limits<double>::infinity();
  EXPECT_THROW((void)search.build(c.input(), infinite), std::invalid_argument);
  // The same box without the conflict is fine, and a particle on a plane lists its coincident image.
  const Cloud on_plane{{0.0}, {0.3}, {0.3}, {0.1}};
  const NeighbourLists lists = search.build(on_plane.input(), mirror_box({0, 0, 0}, {true, false, false}));
  ASSERT_EQ(lists.count(0), 1u);
  EXPECT_EQ(lists.of(0)[0], neighbour_entry(0, 1u));
}

TEST(MirrorSearch, EntryEncoding) {
  EXPECT_EQ(max_search_particles, std::size_t{1} << 29);
  const std::uint32_t e = neighbour_entry(neighbour_index_mask, 5u);
  EXPECT_EQ(neighbour_index(e), neighbour_index_mask);
  EXPECT_EQ(mirror_bits(e), 5u);
  EXPECT_EQ(mirror_bits(neighbour_entry(123, 0u)), 0u);
  // Reflection of a state: the x and xy images of (1, 2, 3) with planes x = -1, y = 0.5.
  MirrorPlanes planes;
  planes.mirrored = {true, true, false};
  planes.position = {-1.0, 0.5, 0.0};
  const MirrorImage image = mirror_image(neighbour_entry(7, 3u));
  EXPECT_EQ(image.index, 7u);
  EXPECT_EQ(image.position(0, planes, 1.0), -3.0);
  EXPECT_EQ(image.position(1, planes, 2.0), -1.0);
  EXPECT_EQ(image.position(2, planes, 3.0), 3.0);
  EXPECT_EQ(image.vector(0, 4.0), -4.0);
  EXPECT_EQ(image.vector(1, 5.0), -5.0);
  EXPECT_EQ(image.vector(2, 6.0), 6.0);
  EXPECT_EQ(image.shear(0, 1, 7.0), 7.0);  // both x and y mirrored: unchanged
  EXPECT_EQ(image.shear(0, 2, 8.0), -8.0);
  EXPECT_EQ(image.shear(1, 2, 9.0), -9.0);
  const MirrorImage x_only = mirror_image(neighbour_entry(7, 1u));
  EXPECT_EQ(x_only.shear(0, 1, 7.0), -7.0);
  EXPECT_EQ(x_only.shear(0, 2, 8.0), -8.0);
  EXPECT_EQ(x_only.shear(1, 2, 9.0), 9.0);
  // Without mirrors the entry is the index and nothing is reflected.
  const MirrorImage plain = mirror_image<false>(123u);
  EXPECT_EQ(plain.index, 123u);
  EXPECT_EQ(plain.position(0, planes, 1.0), 1.0);
}

// Kept lists (update(), block time steps) with two mirror planes: while particles move about near the
// planes (never across), every pair and image pair within h_i + h_j stays listed, each list sorted.
TEST(MirrorNeighbourSearch, KeptListsHoldEveryImagePairWhileParticlesMove) {
  Cloud c = random_cloud(1500, {0.0, 0.0, 0.0}, 0.03, 0.06, 17);
  const Box box = mirror_box({0.0, 0.0, 0.0}, {true, true, false});
  NeighbourSearchOptions options;
  options.skin = 0.2;
  NeighbourSearch search(options);
  NeighbourLists lists;
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::size_t image_pairs = 0;
  for (int round = 0; round < 10; ++round) {
    search.update(c.input(), box, lists, round == 0);
    const auto exact = brute_force(c, box, 0.0);
    for (std::size_t i = 0; i < c.x.size(); ++i) {
      const auto got = lists.of(i);
      ASSERT_TRUE(std::adjacent_find(got.begin(), got.end(), std::greater_equal<>()) == got.end()) << i;
      for (const std::uint32_t e : exact[i]) {
        ASSERT_TRUE(std::binary_search(got.begin(), got.end(), e))
            << "round " << round << ": entry " << e << " of particle " << i << " missing";
        image_pairs += mirror_bits(e) != 0 ? 1 : 0;
      }
    }
    for (std::size_t i = 0; i < c.x.size(); ++i) {
      c.x[i] = std::max(0.0, c.x[i] + 0.006 * unit(rng));
      c.y[i] = std::max(0.0, c.y[i] + 0.006 * unit(rng));
      c.z[i] += 0.006 * unit(rng);
    }
  }
  EXPECT_GT(image_pairs, 1000u);
  EXPECT_GT(search.searches(), c.x.size());
}

// The pairs of list i within h_i + h_j (images placed by their bits), in list order: what a pair loop sums.
std::vector<std::uint32_t> within_support(const NeighbourLists& lists, const Cloud& c, const Box& box,
                                          std::size_t i) {
  std::vector<std::uint32_t> out;
  for (const std::uint32_t e : lists.of(i)) {
    const std::size_t j = neighbour_index(e);
    const unsigned bits = mirror_bits(e);
    const double pj[3] = {c.x[j], c.y[j], c.z[j]};
    const double pi[3] = {c.x[i], c.y[i], c.z[i]};
    double d2 = 0.0;
    for (int a = 0; a < 3; ++a) {
      const double image = ((bits >> a) & 1u) ? 2.0 * box.lower[a] - pj[a] : pj[a];
      d2 += (pi[a] - image) * (pi[a] - image);
    }
    const double reach = c.h[i] + c.h[j];
    if (d2 < reach * reach) out.push_back(e);
  }
  return out;
}

// As an impact run keeps its lists: particles cross the planes a little within a block and are reflected
// back at its end, and every few blocks some leave (ejecta: the stayers keep their order, the leavers go
// behind them). Neither needs a restructure: after each, every pair and image pair within h_i + h_j is
// listed, and the pairs within the support are those of lists searched afresh, in the same order.
TEST(MirrorNeighbourSearch, KeptListsFollowReflectionsAndParticlesThatLeave) {
  Cloud c = random_cloud(1500, {0.0, 0.0, 0.0}, 0.03, 0.06, 23);
  for (std::size_t i = 0; i < c.x.size(); i += 8) {  // some within 0.003 of a plane, some of both
    c.x[i] *= 0.003;
    if (i % 16 == 0) c.y[i] *= 0.003;
  }
  const Box box = mirror_box({0.0, 0.0, 0.0}, {true, true, false});
  NeighbourSearchOptions options;
  options.skin = 0.2;
  NeighbourSearch search(options), fresh(options);
  NeighbourLists lists, fresh_lists;
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::size_t removed = 0, reflected = 0, crossed_pairs = 0;
  const auto check = [&](const char* when, int round) {
    const std::size_t n = c.x.size();
    ASSERT_EQ(lists.particle_count(), n);
    fresh.update(c.input(), box, fresh_lists, true);
    const auto exact = brute_force(c, box, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const auto got = lists.of(i);
      ASSERT_TRUE(std::adjacent_find(got.begin(), got.end(), std::greater_equal<>()) == got.end()) << i;
      for (const std::uint32_t e : got) ASSERT_LT(neighbour_index(e), n) << when << ", round " << round;
      for (const std::uint32_t e : exact[i]) {
        ASSERT_TRUE(std::binary_search(got.begin(), got.end(), e))
            << when << ", round " << round << ": entry " << e << " of particle " << i << " missing";
        if (c.x[i] < 0.0 || c.y[i] < 0.0) ++crossed_pairs;
      }
      ASSERT_EQ(within_support(lists, c, box, i), within_support(fresh_lists, c, box, i))
          << when << ", round " << round << ", particle " << i;
    }
  };
  for (int round = 0; round < 12; ++round) {
    // Within the block: a move that may take particles up to 0.001 across a plane (in 12 blocks less than the
    // margin by which the image bands are widened: no particle comes from beyond them).
    for (std::size_t i = 0; i < c.x.size(); ++i) {
      c.x[i] += 0.001 * unit(rng);
      c.y[i] += 0.001 * unit(rng);
      c.z[i] += 0.006 * unit(rng);
    }
    search.update(c.input(), box, lists, round == 0);
    check("moved", round);
    // At its end: reflected back across the planes, then, every third block, some particles leave.
    for (std::size_t i = 0; i < c.x.size(); ++i) {
      reflected += c.x[i] < 0.0 || c.y[i] < 0.0 ? 1 : 0;
      c.x[i] = std::abs(c.x[i]);
      c.y[i] = std::abs(c.y[i]);
    }
    if (round % 3 == 2) {
      std::vector<std::uint32_t> order, leavers;
      for (std::uint32_t i = 0; i < c.x.size(); ++i)
        (i % 37 == std::uint32_t(round) % 37 ? leavers : order).push_back(i);
      const std::size_t kept = order.size();
      order.insert(order.end(), leavers.begin(), leavers.end());
      Cloud next;
      for (std::size_t k = 0; k < kept; ++k) {
        next.x.push_back(c.x[order[k]]);
        next.y.push_back(c.y[order[k]]);
        next.z.push_back(c.z[order[k]]);
        next.h.push_back(c.h[order[k]]);
      }
      ASSERT_TRUE(search.remove_particles(order, kept, lists));
      removed += c.x.size() - kept;
      c = next;
    }
    search.update(c.input(), box, lists, false);
    check("reflected and left", round);
  }
  EXPECT_GT(reflected, 100u);
  EXPECT_GT(crossed_pairs, 500u);
  EXPECT_GT(removed, 100u);
  EXPECT_EQ(search.restructures(), 1u);  // the first call only
}

}  // namespace
}  // namespace craterkit::sph
