// Neighbour search: lists equal a brute-force O(n^2) search (variable h, open and periodic axes, skin),
// are symmetric, independent of the thread count, and the rebuild criterion is sufficient.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>
#include <stdexcept>
#include <vector>

#include "craterkit/sph/neighbours/neighbour_search.hpp"

namespace craterkit::sph {
namespace {

struct Cloud {
  std::vector<double> x, y, z, h;
  [[nodiscard]] NeighbourInput input() const { return {x, y, z, h}; }
};

// n points uniform in [0, 1)^3 with h in [h_lo, h_hi]; a fraction `scattered` thrown over [-50, 50)^3.
Cloud random_cloud(std::size_t n, double h_lo, double h_hi, double scattered, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Cloud c;
  for (std::size_t i = 0; i < n; ++i) {
    const bool far = unit(rng) < scattered;
    const double scale = far ? 100.0 : 1.0, shift = far ? -50.0 : 0.0;
    c.x.push_back(shift + scale * unit(rng));
    c.y.push_back(shift + scale * unit(rng));
    c.z.push_back(shift + scale * unit(rng));
    c.h.push_back(h_lo + (h_hi - h_lo) * unit(rng));
  }
  return c;
}

// Reference lists written out independently of the library: every pair, minimum image by rounding.
std::vector<std::vector<std::uint32_t>> brute_force(const Cloud& c, const Box& box, double skin) {
  const std::size_t n = c.x.size();
  std::vector<std::vector<std::uint32_t>> lists(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      if (i == j) continue;
      double d[3] = {c.x[i] - c.x[j], c.y[i] - c.y[j], c.z[i] - c.z[j]};
      for (int a = 0; a < 3; ++a) {
        if (box.periodic[a]) {
          const double edge = box.upper[a] - box.lower[a];
          d[a] -= edge * std::round(d[a] / edge);
        }
      }
      const double reach = (1 + skin) * (c.h[i] + c.h[j]);
      if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < reach * reach) lists[i].push_back(std::uint32_t(j));
    }
  }
  return lists;
}

void expect_equal_to_brute_force(const NeighbourLists& lists,
                                 const std::vector<std::vector<std::uint32_t>>& ref) {
  ASSERT_EQ(lists.particle_count(), ref.size());
  ASSERT_EQ(lists.offsets.front(), 0u);
  std::size_t total = 0;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    auto got = std::vector<std::uint32_t>(lists.of(i).begin(), lists.of(i).end());
    std::sort(got.begin(), got.end());
    ASSERT_EQ(got, ref[i]) << "particle " << i;
    total += ref[i].size();
  }
  EXPECT_EQ(lists.total(), total);
}

struct Case {
  double skin;
  std::size_t leaf_size;
};

class NeighbourSearchTest : public ::testing::TestWithParam<Case> {};

TEST_P(NeighbourSearchTest, EqualsBruteForceVariableH) {
  const Cloud c = random_cloud(3000, 0.03, 0.1, 0.0, 1);
  NeighbourSearch search({GetParam().skin, GetParam().leaf_size});
  const NeighbourLists lists = search.build(c.input(), Box{});
  expect_equal_to_brute_force(lists, brute_force(c, Box{}, GetParam().skin));
  EXPECT_GT(lists.mean_neighbours(), 10.0);  // the test must exercise real neighbour sets
}

TEST_P(NeighbourSearchTest, EqualsBruteForceWithScatteredEjectaAndWideH) {
  // 5 % of particles over a 100x larger box, h spanning a factor 20: sparse cells and far tree nodes.
  Cloud c = random_cloud(3000, 0.005, 0.1, 0.05, 2);
  c.h[7] = 3.0;    // one particle with a huge h reaching many others
  c.x[11] = 1e9;   // one particle beyond the 2^21 Morton resolution of the bulk: the bulk shares one key
  c.y[12] = -1e7;  // and the octree must split it at medians (split_at_median)
  NeighbourSearch search({GetParam().skin, GetParam().leaf_size});
  expect_equal_to_brute_force(search.build(c.input(), Box{}), brute_force(c, Box{}, GetParam().skin));
}

TEST_P(NeighbourSearchTest, EqualsBruteForcePeriodic) {
  const Cloud c = random_cloud(2500, 0.02, 0.08, 0.0, 3);
  for (const std::array<bool, 3> periodic :
       {std::array<bool, 3>{true, false, false}, std::array<bool, 3>{true, true, true},
        std::array<bool, 3>{false, true, true}}) {
    const Box box{{0, 0, 0}, {1, 1, 1}, periodic};
    NeighbourSearch search({GetParam().skin, GetParam().leaf_size});
    SCOPED_TRACE(::testing::Message() << periodic[0] << periodic[1] << periodic[2]);
    expect_equal_to_brute_force(search.build(c.input(), box), brute_force(c, box, GetParam().skin));
  }
}

TEST_P(NeighbourSearchTest, PeriodicBoxOnlyFewCellsWideAndPositionsOutsideBox) {
  // Box edge just above 2 x reach (two cells along the axis): neighbours across the boundary must appear
  // once. Positions one box edge outside are wrapped by the search.
  Cloud c = random_cloud(800, 0.1, 0.12, 0.0, 4);
  for (std::size_t i = 0; i < c.x.size(); i += 3) c.x[i] += 1.0;
  const Box box{{0, 0, 0}, {1, 1, 1}, {true, true, true}};
  NeighbourSearch search({0.0, GetParam().leaf_size});
  expect_equal_to_brute_force(search.build(c.input(), box), brute_force(c, box, 0.0));
}

TEST_P(NeighbourSearchTest, ListsAreSymmetric) {
  const Cloud c = random_cloud(5000, 0.005, 0.05, 0.01, 5);
  NeighbourSearch search({GetParam().skin, GetParam().leaf_size});
  const NeighbourLists lists = search.build(c.input(), Box{});
  for (std::size_t i = 0; i < lists.particle_count(); ++i) {
    for (const std::uint32_t j : lists.of(i)) {
      const auto back = lists.of(j);
      ASSERT_NE(std::find(back.begin(), back.end(), std::uint32_t(i)), back.end()) << i << " -> " << j;
    }
  }
}

TEST_P(NeighbourSearchTest, IndependentOfThreadCountAndReusesBuffers) {
  const Cloud c = random_cloud(20000, 0.01, 0.03, 0.01, 6);
  NeighbourSearch search({GetParam().skin, GetParam().leaf_size});
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  NeighbourLists one;
  search.build(c.input(), Box{}, one);
  omp_set_num_threads(2);
  NeighbourLists two;
  search.build(c.input(), Box{}, two);
  search.build(c.input(), Box{}, two);  // a rebuild into the same lists gives the same answer
  search.release_workspace();
  EXPECT_FALSE(search.needs_rebuild(c.input()));  // the build state survives the release
  NeighbourLists three;
  search.build(c.input(), Box{}, three);
  omp_set_num_threads(threads);
  EXPECT_EQ(one.neighbours, three.neighbours);
  EXPECT_EQ(one.offsets, two.offsets);
  EXPECT_EQ(one.neighbours, two.neighbours);  // same order too: sums in the engine are reproducible
}

TEST_P(NeighbourSearchTest, ExactWhenTheSampledCountsMislead) {
  // The lists are written into regions sized from every 16th particle's count. Make exactly those
  // particles isolated, so the regions are far too small and the overflow path must take over.
  Cloud c = random_cloud(4000, 0.04, 0.06, 0.0, 9);
  for (std::size_t i = 0; i < c.x.size(); i += 16) c.x[i] += 1000.0 + double(i);
  NeighbourSearch search({GetParam().skin, GetParam().leaf_size});
  for (const int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    expect_equal_to_brute_force(search.build(c.input(), Box{}), brute_force(c, Box{}, GetParam().skin));
  }
  omp_set_num_threads(2);
}

INSTANTIATE_TEST_SUITE_P(SkinAndLeafSize, NeighbourSearchTest,
                         ::testing::Values(Case{0.0, 4}, Case{0.15, 16}, Case{0.0, 64}, Case{0.15, 64}));

TEST(NeighbourSearch, EdgeCases) {
  NeighbourSearch search;
  const NeighbourLists empty = search.build(NeighbourInput{}, Box{});
  EXPECT_EQ(empty.particle_count(), 0u);
  EXPECT_EQ(empty.total(), 0u);

  // Coincident points are neighbours of each other but not of themselves.
  const Cloud c{{0.5, 0.5, 0.5, 3.0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0.1, 0.1, 0.1, 0.1}};
  const NeighbourLists lists = search.build(c.input(), Box{});
  EXPECT_EQ(lists.count(0), 2u);
  EXPECT_EQ(lists.count(3), 0u);

  // Exactly at r = h_i + h_j is outside (strict inequality).
  const Cloud edge{{0.0, 0.25}, {0, 0}, {0, 0}, {0.125, 0.125}};
  EXPECT_EQ(search.build(edge.input(), Box{}).total(), 0u);
}

TEST(NeighbourSearch, RejectsBadInput) {
  NeighbourSearch search;
  const Cloud bad_h{{0, 1}, {0, 0}, {0, 0}, {0.1, 0.0}};
  EXPECT_THROW((void)search.build(bad_h.input(), Box{}), std::invalid_argument);
  const Cloud nan_h{{0, 1}, {0, 0}, {0, 0}, {0.1, std::nan("")}};
  EXPECT_THROW((void)search.build(nan_h.input(), Box{}), std::invalid_argument);
  const Cloud nan_x{{0, std::nan("")}, {0, 0}, {0, 0}, {0.1, 0.1}};
  EXPECT_THROW((void)search.build(nan_x.input(), Box{}), std::invalid_argument);
  const Cloud short_h{{0, 1}, {0, 0}, {0, 0}, {0.1}};
  EXPECT_THROW((void)search.build(short_h.input(), Box{}), std::invalid_argument);
  // Periodic edge 1 with h = 0.3: pairs could interact through two images.
  const Cloud big_h{{0.1, 0.6}, {0, 0}, {0, 0}, {0.3, 0.3}};
  EXPECT_THROW((void)search.build(big_h.input(), Box{{0, 0, 0}, {1, 1, 1}, {true, false, false}}),
               std::invalid_argument);
  EXPECT_THROW(NeighbourSearch({-0.1, 16}), std::invalid_argument);
  EXPECT_THROW(NeighbourSearch({0.1, 0}), std::invalid_argument);
}

TEST(NeighbourSearch, RebuildCriterionIsSufficient) {
  // Move every particle by random displacements and grow h; whenever needs_rebuild() says no, the old
  // (skinned) lists must still contain every true pair of the new configuration.
  const double skin = 0.2;
  Cloud c = random_cloud(3000, 0.02, 0.05, 0.0, 7);
  NeighbourSearch search({skin, 16});
  const NeighbourLists lists = search.build(c.input(), Box{});
  EXPECT_FALSE(search.needs_rebuild(c.input()));
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int kept = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const double amplitude = 0.001 * (trial + 1);  // from inside to well beyond the skin (0.2 h >= 0.004)
    Cloud moved = c;
    for (std::size_t i = 0; i < c.x.size(); ++i) {
      moved.x[i] += amplitude * unit(rng) / std::sqrt(3.0);
      moved.y[i] += amplitude * unit(rng) / std::sqrt(3.0);
      moved.z[i] += amplitude * unit(rng) / std::sqrt(3.0);
      moved.h[i] *= 1.0 + 0.25 * amplitude * (unit(rng) + 1.0);
    }
    if (search.needs_rebuild(moved.input())) continue;
    ++kept;
    const auto truth = brute_force(moved, Box{}, 0.0);
    for (std::size_t i = 0; i < truth.size(); ++i) {
      const auto have = lists.of(i);
      for (const std::uint32_t j : truth[i]) {
        ASSERT_NE(std::find(have.begin(), have.end(), j), have.end())
            << "trial " << trial << " pair " << i << j;
      }
    }
  }
  EXPECT_GE(kept, 1);   // small moves are accepted...
  EXPECT_LT(kept, 12);  // ...large ones are not
  Cloud one_far = c;
  one_far.x[10] += 1.001 * skin * c.h[10];  // just beyond s h_10
  EXPECT_TRUE(search.needs_rebuild(one_far.input()));
  EXPECT_TRUE(search.needs_rebuild(Cloud{}.input()));  // particle count changed
}

// Every pair within h_i + h_j at the current positions is in the kept lists, and each list is sorted with
// no entry twice. Returns the number of listed entries.
std::size_t expect_kept_lists_cover(const NeighbourLists& lists,
                                    const std::vector<std::vector<std::uint32_t>>& exact, int round) {
  std::size_t entries = 0;
  for (std::size_t i = 0; i < exact.size(); ++i) {
    const auto got = lists.of(i);
    entries += got.size();
    EXPECT_TRUE(std::adjacent_find(got.begin(), got.end(), std::greater_equal<>()) == got.end())
        << "round " << round << ": list " << i << " not strictly ascending";
    for (const std::uint32_t j : exact[i]) {
      if (!std::binary_search(got.begin(), got.end(), j)) {
        ADD_FAILURE() << "round " << round << ": pair (" << i << ", " << j << ") within h_i + h_j is missing";
        return entries;
      }
    }
  }
  return entries;
}

// Block time steps: update() keeps the lists of every particle from call to call, searching again only the
// particles that moved beyond the skin since their last search; right after a restructure the lists are
// exactly the pairs within (1 + s)(h_i + h_j), and after any number of moves they still hold every pair
// within h_i + h_j, sorted, while far fewer lists are searched than a search per call would.
TEST(NeighbourSearch, KeptListsHoldEveryPairWhileParticlesMove) {
  Cloud c = random_cloud(3000, 0.02, 0.06, 0.01, 21);
  const Box box{};  // open
  NeighbourSearchOptions options;
  options.skin = 0.3;
  NeighbourSearch search(options);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  NeighbourLists lists;
  constexpr int rounds = 12;
  for (int round = 0; round < rounds; ++round) {
    search.update(c.input(), box, lists, round == 0);
    ASSERT_EQ(lists.particle_count(), c.x.size());
    if (round == 0) {
      const auto ref = brute_force(c, box, options.skin);
      for (std::uint32_t i = 0; i < c.x.size(); ++i) {
        ASSERT_EQ(std::vector<std::uint32_t>(lists.of(i).begin(), lists.of(i).end()), ref[i])
            << "particle " << i;
      }
    }
    expect_kept_lists_cover(lists, brute_force(c, box, 0.0), round);
    // Motion of a few per cent of h per round, a few particles thrown far, h growing and shrinking.
    for (std::size_t i = 0; i < c.x.size(); ++i) {
      c.x[i] += 0.004 * unit(rng);
      c.y[i] += 0.004 * unit(rng);
      c.z[i] += 0.004 * unit(rng);
      c.h[i] = std::clamp(c.h[i] * (1.0 + 0.01 * unit(rng)), 0.02, 0.06);
      if (i % 997 == 0) c.x[i] += 0.3 * unit(rng);
    }
  }
  // A moved particle whose h outgrows (1 + s) times the build's largest h forces a restructure (the h here
  // grow towards 0.06): at most a few, not one per round.
  EXPECT_LE(search.restructures(), 3u);
  EXPECT_GT(search.searches(), c.x.size());               // some particles were searched again
  EXPECT_LT(search.searches(), c.x.size() * rounds / 3);  // most lists were kept
}

// The lists' content does not depend on the thread count, and a restructure at any call gives lists that
// hold the same pairs within h_i + h_j in the same order (what the pair loops sum).
TEST(NeighbourSearch, KeptListsSumTheSamePairsWhateverTheirHistory) {
  Cloud c = random_cloud(2000, 0.03, 0.06, 0.0, 8);
  const Box box{{0, 0, 0}, {1, 1, 1}, {true, false, true}};
  NeighbourSearchOptions options;
  options.skin = 0.2;
  NeighbourSearch kept(options), fresh(options);
  NeighbourLists kept_lists, fresh_lists;
  const int threads = omp_get_max_threads();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int round = 0; round < 8; ++round) {
    omp_set_num_threads(1 + round % 2);
    kept.update(c.input(), box, kept_lists, round == 0);
    fresh.update(c.input(), box, fresh_lists, true);
    for (std::size_t i = 0; i < c.x.size(); ++i) {
      const auto within = [&](const NeighbourLists& lists) {
        std::vector<std::uint32_t> out;
        for (const std::uint32_t j : lists.of(i)) {
          double d[3] = {c.x[i] - c.x[j], c.y[i] - c.y[j], c.z[i] - c.z[j]};
          for (int a = 0; a < 3; ++a) d[a] = minimum_image(box, a, d[a]);
          const double reach = c.h[i] + c.h[j];
          if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < reach * reach) out.push_back(j);
        }
        return out;
      };
      ASSERT_EQ(within(kept_lists), within(fresh_lists)) << "round " << round << ", particle " << i;
    }
    for (std::size_t i = 0; i < c.x.size(); ++i) {
      c.x[i] = wrap_position(box, 0, c.x[i] + 0.005 * unit(rng));
      c.y[i] += 0.005 * unit(rng);
      c.z[i] = wrap_position(box, 2, c.z[i] + 0.005 * unit(rng));
    }
  }
  omp_set_num_threads(threads);
  EXPECT_EQ(kept.restructures(), 1u);
}

// update_moved() with the particles that may have left their skins named gives update()'s lists entry for
// entry, reading no other particle's position: the candidates are those whose room() the round's motion
// could have used up, and every other particle is given a wrong position, which must not matter. The
// candidates are a small part of the particles. When a restructure is due it declines and changes nothing.
TEST(NeighbourSearch, CheckingOnlyTheCandidatesKeepsTheSameLists) {
  Cloud c = random_cloud(3000, 0.02, 0.06, 0.0, 17);
  const Box box{{0, 0, 0}, {1, 1, 1}, {true, false, false}};
  NeighbourSearchOptions options;
  options.skin = 0.2;
  NeighbourSearch every(options), named(options);
  NeighbourLists every_lists, named_lists;
  every.update(c.input(), box, every_lists, true);
  named.update(c.input(), box, named_lists, true);
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<double> room(c.x.size());
  std::size_t named_total = 0, moved_total = 0;
  for (int round = 0; round < 10; ++round) {
    for (std::size_t i = 0; i < c.x.size(); ++i) room[i] = named.room(i, c.x[i], c.y[i], c.z[i], c.h[i], box);
    // Each particle moves by at most 0.001 * sqrt(3) and its h grows by at most 0.0005, a few far.
    std::vector<std::uint32_t> candidates;
    Cloud hidden = c;  // the positions update_moved() sees: wrong for every particle it is not given
    for (std::size_t i = 0; i < c.x.size(); ++i) {
      const bool far = (i + std::size_t(round)) % 331 == 0;
      const double step = far ? 0.05 : 0.001;
      c.x[i] = wrap_position(box, 0, c.x[i] + step * unit(rng));
      c.y[i] += step * unit(rng);
      c.z[i] += step * unit(rng);
      c.h[i] = std::min(0.06, c.h[i] + 0.00025 * (1.0 + unit(rng)));
      if (far || room[i] <= 0.001 * std::sqrt(3.0) + 0.0005) {
        candidates.push_back(std::uint32_t(i));
        hidden.x[i] = c.x[i];
        hidden.y[i] = c.y[i];
        hidden.z[i] = c.z[i];
        hidden.h[i] = c.h[i];
      } else {
        hidden.x[i] = -7.0;  // would be found moved if it were read
      }
    }
    every.update(c.input(), box, every_lists, false);
    ASSERT_TRUE(named.update_moved(hidden.input(), box, named_lists, candidates)) << "round " << round;
    ASSERT_EQ(std::vector<std::uint32_t>(named.moved().begin(), named.moved().end()),
              std::vector<std::uint32_t>(every.moved().begin(), every.moved().end()))
        << "round " << round;
    for (std::size_t i = 0; i < c.x.size(); ++i) {
      ASSERT_EQ(std::vector<std::uint32_t>(named_lists.of(i).begin(), named_lists.of(i).end()),
                std::vector<std::uint32_t>(every_lists.of(i).begin(), every_lists.of(i).end()))
          << "round " << round << ", particle " << i;
    }
    named_total += candidates.size();
    moved_total += named.moved().size();
  }
  EXPECT_GT(moved_total, 0u);
  EXPECT_LT(named_total, c.x.size() * 10 / 4);
  EXPECT_EQ(every.restructures(), 1u);
  // A candidate grown beyond (1 + s) times the build's largest h needs a restructure: declined, unchanged.
  const NeighbourLists before = named_lists;
  Cloud grown = c;
  grown.h[5] = 1.0;
  const std::vector<std::uint32_t> one{5};
  EXPECT_FALSE(named.update_moved(grown.input(), box, named_lists, one));
  EXPECT_EQ(named_lists.neighbours, before.neighbours);
  EXPECT_EQ(named_lists.ends, before.ends);
  EXPECT_TRUE(named.moved().empty());
  EXPECT_EQ(named.restructures(), 1u);
}

// Kept lists are laid out in their slots where they were collected: the search holds no second copy of
// them (its work buffers are a fraction of the entries the lists use).
TEST(NeighbourSearch, KeptListsAreHeldOnce) {
  Cloud c = random_cloud(4000, 0.07, 0.08, 0.0, 13);
  NeighbourSearchOptions options;
  options.skin = 0.1;
  NeighbourSearch search(options);
  NeighbourLists lists;
  search.update(c.input(), Box{}, lists, true);
  const double entry_bytes = double(lists.total()) * sizeof(std::uint32_t);
  ASSERT_GT(lists.total(), 40u * c.x.size());
  EXPECT_LT(double(search.workspace_bytes()), 0.75 * entry_bytes);
  EXPECT_LT(double(lists.bytes()), 1.6 * entry_bytes) << "slots with a quarter more room, plus a little";
}

// What the kept lists and their search hold between restructures: slots with an eighth more room (and two
// entries) in an array with a sixteenth more for moved slots, and none of the buffers that only the
// collection of the lists reads (sort keys, sorted index -> group, candidate groups: at least 20 bytes per
// particle that a build() keeps). Particles that move afterwards are still found.
TEST(NeighbourSearch, KeptListsHoldLittleRoomAndNoBuildBuffers) {
  Cloud c = random_cloud(4000, 0.07, 0.08, 0.0, 13);
  NeighbourSearchOptions options;
  options.skin = 0.1;
  NeighbourSearch kept(options), built(options);
  NeighbourLists lists, packed;
  kept.update(c.input(), Box{}, lists, true);
  built.build(c.input(), Box{}, packed);
  const double n = double(c.x.size());
  const double entry_bytes = double(lists.total()) * sizeof(std::uint32_t);
  ASSERT_GT(lists.total(), 40u * c.x.size());
  // Offsets and ends 16 bytes, two entries and a sixteenth of the array 8.5 bytes per particle: 1.2 times the
  // entries and 24.5 bytes per particle (a quarter more room and four entries in an eighth more: 1.41 and
  // 34).
  EXPECT_LT(double(lists.bytes()), 1.25 * entry_bytes + 24.0 * n);
  // The kept search holds its slot ends (8 bytes per particle) and no keys or candidates.
  EXPECT_LT(double(kept.workspace_bytes()) + 20.0 * n, double(built.workspace_bytes()) + 8.0 * n);
  // Moved particles are searched again with the released buffers gone, and the lists stay exact supersets.
  for (std::size_t i = 0; i < c.x.size(); i += 7) c.x[i] += 0.02;  // beyond the skin 0.1 h
  kept.update(c.input(), Box{}, lists, false);
  EXPECT_EQ(kept.restructures(), 1u);
  const NeighbourLists exact = NeighbourSearch().build(c.input(), Box{});
  for (std::size_t i = 0; i < c.x.size(); ++i) {
    const auto have = lists.of(i);
    for (const std::uint32_t j : exact.of(i)) {
      ASSERT_NE(std::find(have.begin(), have.end(), j), have.end()) << i << " misses " << j;
    }
  }
}

TEST(NeighbourSearch, MinimumImageAndWrap) {
  const Box box{{-1, 0, 0}, {1, 10, 1}, {true, false, true}};
  EXPECT_DOUBLE_EQ(minimum_image(box, 0, 1.5), -0.5);
  EXPECT_DOUBLE_EQ(minimum_image(box, 0, -1.5), 0.5);
  EXPECT_DOUBLE_EQ(minimum_image(box, 0, 0.9), 0.9);
  EXPECT_DOUBLE_EQ(minimum_image(box, 1, 9.0), 9.0);  // open axis untouched
  const auto d = displacement(box, 0.95, 1.0, 0.05, -0.95, 3.0, 0.95);
  EXPECT_NEAR(d[0], -0.1, 1e-12);
  EXPECT_DOUBLE_EQ(d[1], -2.0);
  EXPECT_NEAR(d[2], 0.1, 1e-12);
  EXPECT_DOUBLE_EQ(wrap_position(box, 0, 1.25), -0.75);
  EXPECT_DOUBLE_EQ(wrap_position(box, 0, -3.5), 0.5);
  EXPECT_DOUBLE_EQ(wrap_position(box, 0, 1.0), -1.0);
  EXPECT_DOUBLE_EQ(wrap_position(box, 1, 12.0), 12.0);
}

// Particles leaving kept lists (ejecta): the lists of the stayers lose them and are renumbered, with the
// pairs within the support those of a fresh search, in the same order; later calls keep them without a
// restructure. Lists of build(), and orders that do not keep the stayers ascending, are refused untouched.
TEST(NeighbourSearch, KeptListsLoseParticlesThatLeave) {
  Cloud c = random_cloud(2000, 0.03, 0.06, 0.0, 12);
  const Box box{};
  NeighbourSearchOptions options;
  options.skin = 0.2;
  NeighbourSearch search(options), fresh(options);
  NeighbourLists lists, fresh_lists;
  search.update(c.input(), box, lists, true);
  for (int round = 0; round < 3; ++round) {
    std::vector<std::uint32_t> order, leavers;
    for (std::uint32_t i = 0; i < c.x.size(); ++i)
      (i % 23 == std::uint32_t(round) ? leavers : order).push_back(i);
    const std::size_t kept = order.size();
    order.insert(order.end(), leavers.begin(), leavers.end());
    Cloud next;
    for (std::size_t k = 0; k < kept; ++k) {
      next.x.push_back(c.x[order[k]] + 0.002);  // and a small move, within the skin
      next.y.push_back(c.y[order[k]]);
      next.z.push_back(c.z[order[k]]);
      next.h.push_back(c.h[order[k]]);
    }
    ASSERT_TRUE(search.remove_particles(order, kept, lists));
    c = next;
    search.update(c.input(), box, lists, false);
    fresh.update(c.input(), box, fresh_lists, true);
    expect_kept_lists_cover(lists, brute_force(c, box, 0.0), round);
    for (std::size_t i = 0; i < c.x.size(); ++i) {
      const auto within = [&](const NeighbourLists& l) {
        std::vector<std::uint32_t> out;
        for (const std::uint32_t j : l.of(i)) {
          EXPECT_LT(j, c.x.size());
          const double d[3] = {c.x[i] - c.x[j], c.y[i] - c.y[j], c.z[i] - c.z[j]};
          const double reach = c.h[i] + c.h[j];
          if (d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < reach * reach) out.push_back(j);
        }
        return out;
      };
      ASSERT_EQ(within(lists), within(fresh_lists)) << "round " << round << ", particle " << i;
    }
  }
  EXPECT_EQ(search.restructures(), 1u);

  const std::size_t n = c.x.size();
  std::vector<std::uint32_t> swapped(n);
  for (std::uint32_t i = 0; i < n; ++i) swapped[i] = i;
  std::swap(swapped[0], swapped[1]);
  const NeighbourLists before = lists;
  EXPECT_FALSE(search.remove_particles(swapped, n - 1, lists));  // stayers not ascending
  EXPECT_EQ(lists.neighbours, before.neighbours);
  EXPECT_EQ(lists.offsets, before.offsets);
  NeighbourSearch global(options);
  NeighbourLists built = global.build(c.input(), box);
  std::vector<std::uint32_t> identity(n);
  for (std::uint32_t i = 0; i < n; ++i) identity[i] = i;
  EXPECT_FALSE(global.remove_particles(identity, n - 1, built));  // not kept lists: build afresh
}

}  // namespace
}  // namespace craterkit::sph
