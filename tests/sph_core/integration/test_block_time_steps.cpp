// Block time steps (block_time_steps.hpp): the level rule, the schedule of a block (every particle
// takes 2^level steps that tile the block, no particle more than neighbour_levels() coarser than a neighbour,
// at one and at two levels), the schedule on a chain whose one particle needs a short step, and the block
// length with the least work.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "craterkit/sph/integration/block_time_steps.hpp"

using namespace craterkit::sph;

TEST(BlockLevel, SmallestLevelWithinTheLimit) {
  EXPECT_EQ(block_level(1.0, 1.0), 0);
  EXPECT_EQ(block_level(1.0, 2.0), 0);
  EXPECT_EQ(block_level(1.0, std::numeric_limits<double>::infinity()), 0);
  EXPECT_EQ(block_level(1.0, 0.5), 1);
  EXPECT_EQ(block_level(1.0, 0.4999999), 2);
  EXPECT_EQ(block_level(1.0, 0.25), 2);
  EXPECT_EQ(block_level(3.0, 0.1), 5);  // 3/32 = 0.094 <= 0.1 < 3/16
  EXPECT_EQ(block_level(1.0, std::ldexp(1.0, -40)), 40);
  EXPECT_GT(block_level(1.0, 0.0), block_finest_level_limit);
  EXPECT_GT(block_level(1.0, 1e-300), block_finest_level_limit);
  EXPECT_GT(block_level(1.0, std::nan("")), block_finest_level_limit);  // NaN: an error, not level 0
}

// The level by its definition, the smallest l >= 0 with block 2^-l <= step (up to the collapse limit, beyond
// which any level above the limit is the answer), counted up one level at a time
// with ldexp, against block_level (which starts from log2 of the ratio and multiplies by 2^-l from a table),
// over blocks and steps spread across many octaves and placed on and next to the levels.
TEST(BlockLevel, AgreesWithTheDefinitionEverywhere) {
  const auto by_definition = [](double block, double step) {
    int level = 0;
    while (std::ldexp(block, -level) > step && level <= block_finest_level_limit) ++level;
    return level;
  };
  std::uint64_t state = 12345;
  const auto uniform = [&state] {  // 64-bit LCG (Knuth), top 53 bits
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) * 0x1p-53;
  };
  for (int k = 0; k < 20000; ++k) {
    const double block = std::ldexp(0.5 + uniform(), static_cast<int>(80 * uniform()) - 40);
    double step = block * std::exp2(-60.0 * uniform());
    if (k % 4 == 1) step = std::ldexp(block, -static_cast<int>(50 * uniform()));  // exactly on a level
    if (k % 4 == 2)
      step = std::nextafter(std::ldexp(block, -static_cast<int>(50 * uniform())), 0.0);  // below
    const int expected = by_definition(block, step);
    if (expected > block_finest_level_limit) {  // a collapsed step: any level beyond the limit
      ASSERT_GT(block_level(block, step), block_finest_level_limit) << "block " << block << ", step " << step;
    } else {
      ASSERT_EQ(block_level(block, step), expected) << "block " << block << ", step " << step;
    }
  }
}

namespace {

// Particle steps per unit time with a block of length `block`: each particle takes 2^level steps per block.
double steps_per_time(double block, const std::vector<double>& step, const std::vector<std::uint8_t>& flags) {
  double steps = 0.0;
  for (std::size_t i = 0; i < step.size(); ++i)
    if ((flags[i] & (particle_fixed | particle_ejected)) == 0)
      steps += std::ldexp(1.0, block_level(block, step[i]));
  return steps / block;
}

double chosen_block(double longest, const std::vector<double>& step, const std::vector<std::uint8_t>& flags) {
  BlockStepTally tally{};
  tally_block_steps(longest, step, flags, step.size(), tally);
  return cheapest_block_length(longest, tally, 0.0);
}

}  // namespace

// An impact target's bulk steps at 0.87 of the longest step: with the block at the longest step it would
// step half of that; the chosen block lets it step at its own limit, within one bin.
TEST(BlockLength, TheBulkStepsAtItsOwnLimit) {
  std::vector<double> step(1000, 0.87);
  step.push_back(1.0);
  for (int k = 0; k < 50; ++k) step.push_back(0.87 / 8.0);  // a finer core
  const std::vector<std::uint8_t> flags(step.size(), 0);
  const double block = chosen_block(1.0, step, flags);
  EXPECT_LE(block, 0.87);
  EXPECT_GT(block, 0.87 / (1.0 + 1.0 / double(block_length_phases)));
  EXPECT_EQ(block_level(block, 0.87), 0);
  EXPECT_EQ(block_level(block, 0.87 / 8.0), 3);
  EXPECT_LT(steps_per_time(block, step, flags), 0.6 * steps_per_time(1.0, step, flags));
}

// A block's passes over every particle (block_work steps per particle) are paid once more per block: 1,000
// particles at 0.6 L save half their steps with a block of 0.6 L, which costs 1 / 0.6 = 1.67 times the
// blocks. Without that work the shorter block is cheaper (1,673 against 2,001 steps per L); with half a step
// per particle per block it is not (2,510 against 2,501).
TEST(BlockLength, ThePassesOverEveryParticleCountPerBlock) {
  std::vector<double> step(1000, 0.6);
  step.push_back(1.0);
  const std::vector<std::uint8_t> flags(step.size(), 0);
  BlockStepTally tally{};
  tally_block_steps(1.0, step, flags, step.size(), tally);
  EXPECT_EQ(tally[block_tally_particles], 1001.0);
  EXPECT_EQ(tally[block_tally_steps], 1001.0);
  EXPECT_EQ(tally[block_tally_shorter + 42], 1000.0);  // 1 / 0.6 = 1 + 42.67 / 64
  EXPECT_LE(cheapest_block_length(1.0, tally, 0.0), 0.6);
  EXPECT_EQ(cheapest_block_length(1.0, tally, 0.5), 1.0);
}

// Where no shift helps, the block stays the longest step: every particle at one step, or every one at or
// above the block (the global scheme, block_levels = 0), or every step a power-of-two fraction of it.
TEST(BlockLength, TheLongestStepWhereNoShiftSavesSteps) {
  const std::vector<std::uint8_t> flags(8, 0);
  EXPECT_EQ(chosen_block(0.3, std::vector<double>(8, 0.3), flags), 0.3);
  EXPECT_EQ(chosen_block(0.3, std::vector<double>{0.3, 0.5, 1.0, 0.3, 0.4, 0.3, 2.0, 0.3}, flags), 0.3);
  EXPECT_EQ(chosen_block(1.0, std::vector<double>{1.0, 0.5, 0.25, 0.125, 1.0, 0.5, 0.25, 1.0}, flags), 1.0);
}

// Against a brute-force search (every particle's level by block_level at 4,097 block lengths in [L/2, L]):
// the chosen block needs at most 1 + 1/block_length_phases times the fewest steps found, and never more than
// the longest step does. Steps spread log-uniformly over 8 octaves and in clusters, with fixed and ejected
// particles (not counted, whatever their steps); the tally of two halves added is the tally of the whole.
TEST(BlockLength, WithinOneBinOfTheFewestStepsByBruteForce) {
  std::uint64_t state = 987654321;
  const auto uniform = [&state] {  // 64-bit LCG (Knuth), top 53 bits
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) * 0x1p-53;
  };
  for (int trial = 0; trial < 40; ++trial) {
    const std::size_t n = 500 + static_cast<std::size_t>(2000 * uniform());
    std::vector<double> step(n);
    std::vector<std::uint8_t> flags(n, 0);
    const double centres[3] = {std::exp2(-8.0 * uniform()), std::exp2(-8.0 * uniform()),
                               std::exp2(-8.0 * uniform())};
    for (std::size_t i = 0; i < n; ++i) {
      step[i] =
          trial % 2 == 0 ? std::exp2(-8.0 * uniform()) : centres[i % 3] * (1.0 + 0.02 * (uniform() - 0.5));
      if (i % 17 == 0) flags[i] = particle_fixed;
      if (i % 23 == 0) flags[i] = particle_ejected;
      if (i % 17 == 0 || i % 23 == 0) step[i] = 1e-6 * uniform();  // would dominate if counted
    }
    double longest = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      if (flags[i] == 0) longest = std::max(longest, step[i]);
    const double block = chosen_block(longest, step, flags);
    ASSERT_LE(block, longest);
    ASSERT_GE(block, longest / 2.0);
    double fewest = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= 4096; ++k)
      fewest = std::min(fewest, steps_per_time(longest / (1.0 + k / 4096.0), step, flags));
    const double chosen = steps_per_time(block, step, flags);
    EXPECT_LE(chosen, fewest * (1.0 + 1.0 / double(block_length_phases)) * (1.0 + 1e-12))
        << "trial " << trial;
    EXPECT_LE(chosen, steps_per_time(longest, step, flags) * (1.0 + 1e-12)) << "trial " << trial;

    BlockStepTally whole{}, halves{};
    tally_block_steps(longest, step, flags, n, whole);
    tally_block_steps(longest, std::span(step).subspan(n / 2), std::span(flags).subspan(n / 2), n - n / 2,
                      halves);
    tally_block_steps(longest, step, flags, n / 2, halves);
    EXPECT_EQ(cheapest_block_length(longest, halves, 0.0), block);
    EXPECT_TRUE(whole == halves);
  }
}

namespace {

// A chain 0 - 1 - 2 - ... - (n-1): each particle's neighbours are the next and the previous one.
NeighbourLists chain(std::size_t n) {
  NeighbourLists lists;
  lists.offsets.push_back(0);
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0) lists.neighbours.push_back(static_cast<std::uint32_t>(i - 1));
    if (i + 1 < n) lists.neighbours.push_back(static_cast<std::uint32_t>(i + 1));
    lists.offsets.push_back(lists.neighbours.size());
  }
  return lists;
}

}  // namespace

TEST(BlockSchedule, NeighbourRuleAndEveryStepTilesTheBlock) {
  const std::size_t n = 12;
  const auto lists = chain(n);
  std::vector<double> step(n, 1.0);
  step[3] = 1.0 / 64;  // level 6
  std::vector<std::uint8_t> flags(n, particle_active);
  flags[11] = particle_fixed;  // not scheduled
  for (const int neighbour_levels : {1, 2}) {
    SCOPED_TRACE("neighbour levels " + std::to_string(neighbour_levels));
    BlockSchedule s;
    if (neighbour_levels != block_neighbour_levels) s.set_neighbour_levels(neighbour_levels);
    s.start(1.0, step, flags, n, lists);
    EXPECT_EQ(s.neighbour_levels(), neighbour_levels);
    EXPECT_EQ(s.finest_level(), 6);
    // Levels fall by neighbour_levels per hop away from particle 3.
    std::vector<int> expected(n - 1);
    for (std::size_t i = 0; i + 1 < n; ++i) {
      const int hops = std::abs(int(i) - 3);
      expected[i] = std::max(0, 6 - neighbour_levels * hops);
    }
    std::vector<int> activations(n, 0);
    std::vector<double> elapsed(n, 0.0);
    double time = 0.0;
    int substeps = 0;
    while (!s.finished()) {
      time += s.advance();
      ++substeps;
      for (const auto i : s.active()) {
        ++activations[i];
        elapsed[i] += s.active_steps()[i];
        EXPECT_DOUBLE_EQ(elapsed[i], time) << "particle " << i << " ends its step at the tick";
      }
      s.relevel(step, lists);
    }
    EXPECT_EQ(substeps, 64);
    EXPECT_DOUBLE_EQ(time, 1.0);
    for (std::size_t i = 0; i + 1 < n; ++i) {
      EXPECT_EQ(activations[i], 1 << expected[i]) << "particle " << i;
      EXPECT_DOUBLE_EQ(elapsed[i], 1.0);
    }
    EXPECT_EQ(activations[11], 0);  // fixed
  }
}

TEST(BlockSchedule, NeighbourLevelsChangeAtTheNextBlockAndMustBePositive) {
  const auto lists = chain(3);
  const std::vector<double> step{1.0 / 16, 1.0, 1.0};  // level 4
  const std::vector<std::uint8_t> flags(3, particle_active);
  BlockSchedule s;
  s.start(1.0, step, flags, 3, lists);
  EXPECT_EQ(int(s.levels()[1]), 3);
  s.set_neighbour_levels(2);
  EXPECT_EQ(s.neighbour_levels(), block_neighbour_levels) << "not within the block under way";
  while (!s.finished()) {
    (void)s.advance();
    s.relevel(step, lists);
    EXPECT_EQ(int(s.levels()[1]), 3);
  }
  s.start(1.0, step, flags, 3, lists);
  EXPECT_EQ(s.neighbour_levels(), 2);
  EXPECT_EQ(int(s.levels()[1]), 2);
  EXPECT_EQ(int(s.levels()[2]), 0);
  EXPECT_THROW(s.set_neighbour_levels(0), std::invalid_argument);
}

TEST(BlockSchedule, LevelsRefineWithinTheBlockAndCoarsenOnlyWhereAligned) {
  const std::size_t n = 3;
  const auto lists = chain(n);
  std::vector<double> step{1.0, 1.0, 1.0};
  const std::vector<std::uint8_t> flags(n, particle_active);
  BlockSchedule s;
  s.start(1.0, step, flags, n, lists);
  ASSERT_EQ(s.finest_level(), 0);
  // Particle 0 starts at level 1 (half the block).
  step = {0.5, 1.0, 1.0};
  s.start(1.0, step, flags, n, lists);
  ASSERT_EQ(s.finest_level(), 1);
  (void)s.advance();  // tick 1 of 2: particle 0 ends its first half step
  ASSERT_EQ(s.active().size(), 1u);
  // It now needs 1/8: two more levels, inside the block.
  step[0] = 0.125;
  s.relevel(step, lists);
  EXPECT_EQ(s.finest_level(), 3);
  double time = 0.5;
  int count = 0;
  while (!s.finished()) {
    time += s.advance();
    ++count;
    // Wants to go back to the block step at once: coarsens one level at a time, where aligned.
    step[0] = 1.0;
    s.relevel(step, lists);
  }
  EXPECT_DOUBLE_EQ(time, 1.0);
  // From 0.5 with 1/8 to 0.625; 1/4 is not aligned there (0.625 / 0.25 is not whole), so 1/8 again to
  // 0.75, which is aligned to 1/4: to 1.0. Three substeps.
  EXPECT_EQ(count, 3);
}

// Waking: particles 0 and 1 end their steps together; 0 now needs level 6 and wakes its neighbour 1, which
// had chosen level 1, to level 5, cut short at the next tick of that level. 1's new level does not wake 2 in
// the same tick (a woken particle wakes nobody: the result does not depend on the order of the particles, nor
// on how they are spread over processes); 2 is woken when 1's shortened step ends. Every step still tiles the
// block.
TEST(BlockSchedule, TheFinestWakerDecidesAndAWokenParticleWakesNobody) {
  const std::size_t n = 4;
  const auto lists = chain(n);
  const std::vector<std::uint8_t> flags(n, particle_active);
  for (const int neighbour_levels : {1, 2}) {
    SCOPED_TRACE("neighbour levels " + std::to_string(neighbour_levels));
    std::vector<double> step{0.5, 0.5, 1.0, 1.0};
    BlockSchedule s;
    s.set_neighbour_levels(neighbour_levels);
    s.start(1.0, step, flags, n, lists);
    ASSERT_EQ(s.finest_level(), 1);
    double time = s.advance();
    ASSERT_EQ(s.active().size(), 2u);  // 0 and 1, at half the block
    step[0] = 1.0 / 64;
    s.relevel(step, lists);
    EXPECT_EQ(s.finest_level(), 6);
    EXPECT_EQ(int(s.levels()[0]), 6);
    EXPECT_EQ(int(s.levels()[1]), 6 - neighbour_levels);  // woken from 1
    EXPECT_EQ(int(s.levels()[2]), 0);                     // not by the woken 1
    std::vector<double> elapsed(n, 0.0);
    for (const auto i : s.active()) elapsed[i] += s.active_steps()[i];
    bool two_woken = false;
    while (!s.finished()) {
      time += s.advance();
      for (const auto i : s.active()) elapsed[i] += s.active_steps()[i];
      const bool one_ended = std::find(s.active().begin(), s.active().end(), 1u) != s.active().end();
      s.relevel(step, lists);
      if (one_ended && !two_woken) {
        EXPECT_EQ(int(s.levels()[2]), 6 - 2 * neighbour_levels) << "woken by 1 when its own step ended";
        two_woken = true;
      }
    }
    EXPECT_TRUE(two_woken);
    EXPECT_DOUBLE_EQ(time, 1.0);
    for (std::size_t i = 0; i < n; ++i) EXPECT_DOUBLE_EQ(elapsed[i], 1.0) << "particle " << i;
  }
}

TEST(BlockSchedule, CollapsedStepIsAnErrorThatNamesTheParticle) {
  const auto lists = chain(3);
  const std::vector<double> step{1.0, 1e-300, 1.0};
  const std::vector<std::uint8_t> flags(3, particle_active);
  BlockSchedule s;
  try {
    s.start(1.0, step, flags, 3, lists);
    FAIL() << "no exception";
  } catch (const TimeStepCollapse& e) {
    EXPECT_EQ(e.particle, 1u);  // the simulation reports this particle's state and limits
    EXPECT_NE(std::string(e.what()).find("1e-300 s needs more than 50 halvings"), std::string::npos)
        << e.what();
  }
}

// What the schedule holds per particle is counted (Simulation::bytes_per_particle reads it): at least its
// level, scheduled mark, wake floor, the start and end ticks and the step of each particle.
TEST(BlockSchedule, BytesCountThePerParticleArrays) {
  const std::size_t n = 1000;
  const auto lists = chain(n);
  const std::vector<double> step(n, 1.0);
  const std::vector<std::uint8_t> flags(n, particle_active);
  BlockSchedule s;
  EXPECT_EQ(s.bytes(), 0u);
  s.start(1.0, step, flags, n, lists);
  const std::size_t per_particle = 3 * sizeof(std::uint8_t) + 2 * sizeof(std::uint64_t) + sizeof(double);
  EXPECT_GE(s.bytes(), n * per_particle);
  EXPECT_LT(s.bytes(), n * (per_particle + 2 * sizeof(std::uint32_t) + 8));  // and little more
}
