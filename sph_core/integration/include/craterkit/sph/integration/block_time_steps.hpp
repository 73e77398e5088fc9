#pragma once
// Block (individual, power-of-two) time steps (docs/physics.md section 1: "small or fast particles then do
// not hold the whole system to their step"), as in GADGET-2 (Springel 2005, section 4) and Phantom
// (Price et al. 2018, section 2.3.4), on the KDK integrator of integrator.hpp.
//
// A block of length B is one synchronised step of the whole system: every particle starts a step at
// its beginning and ends one at its end. Inside it, particle i takes steps B / 2^l_i (its level l_i),
// with l_i the smallest level whose step does not exceed its own limit Particles::time_step
// (time_step.hpp). Time inside the block is counted in integer ticks, 2^F per block for the finest
// level F in use, so that step ends coincide exactly. At every tick where some particle's step ends:
//   every moving particle drifts to that tick along its own step's extrapolation (drift()),
//   the particles whose step ends there ("active") get their rates from the predicted state of all
//   particles, are corrected with their own step and start a new one, at a new level.
// Level changes (Saitoh & Makino 2009, ApJ 697, L99, section 2, for the neighbour rule):
//   - finer at the end of any step (a step ending at tick t is aligned to every finer level);
//   - coarser by one level at most, and only where the new, longer step is aligned (t a multiple of it);
//   - never more than neighbour_levels() levels coarser than any neighbour (a neighbour's step at most 2 or
//     4 times shorter at one or two levels; Simulation takes one in the shock stage, two after the
//     late-stage switch). At the start of a block the rule is applied to all particles until it holds;
//     inside a block it is applied to each particle when its step ends, and a neighbour in the middle of a
//     step that the rule forbids is woken: its step is cut short at the next tick aligned to the allowed
//     level, and it continues at that level (Saitoh & Makino 2009: without waking, a blast wave reaches
//     cold gas that is still in a long step). The particles that wake are those whose step just ended, at
//     their new levels; a particle woken does not wake others in the same tick (so the result does not
//     depend on the order in which they are visited, nor on how the particles are spread over processes).
// The block length is the longest particle step, at most 2^max_levels times the shortest one and at
// most max_step; at max_levels = 0 the block is the global step and every particle has level 0, which
// is exactly the global scheme. Inside a block a particle may go finer than max_levels (a limit that
// fell during the block is always honoured); more than 50 levels is a collapsed time step.
//
// Conservation: pair forces are evaluated at the same time for both particles only when both are active,
// so momentum and energy are conserved to the integration error, not to round-off as with a global step.
#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "craterkit/sph/neighbours/neighbour_search.hpp"
#include "craterkit/sph/neighbours/pair_support.hpp"
#include "craterkit/sph/particles/particles.hpp"

namespace craterkit::sph {

constexpr int block_finest_level_limit = 50;

// Thrown when a particle's step needs more than block_finest_level_limit halvings of the block: `particle`
// is its index, so that the caller can say which particle and which limit (Simulation does).
struct TimeStepCollapse : std::runtime_error {
  TimeStepCollapse(const std::string& what, std::size_t particle_index)
      : std::runtime_error(what), particle(particle_index) {}
  std::size_t particle;
};
// A particle is at most this many levels coarser than any neighbour (its step at most 2^this longer): the
// schedule's default, kept in the shock stage. Saitoh & Makino (2009) and SWIFT (Schaller et al. 2024,
// section 3.4) allow two levels (a factor 4); docs/physics.md section 1.12 says where the engine does.
inline constexpr int block_neighbour_levels = 1;

// The smallest level l >= 0 with block / 2^l <= step (0 when step >= block).
[[nodiscard]] int block_level(double block, double step);

// Choosing the block length. Power-of-two levels round every particle's step down, by up to a factor 2: with
// the block at the longest step L, a particle whose own step is 0.87 L steps L / 2. A block L / mu (1 <= mu
// <= 2) shifts the levels' phase: the particles with L / step_i = m_i 2^n_i, 1 <= m_i < 2, step 2^-n_i L / mu
// where m_i <= mu and half that where m_i > mu, so the work per unit time is
//     mu / L (count(step_i >= L) + sum over the others of 2^n_i (2 if m_i > mu, else 1) + w M),
// in particle steps, with w M the work of a block's passes over all M moving particles (the drift at every
// substep, the schedule's start) counted as w steps per particle. The block length minimises it
// (docs/physics.md section 1.12). The mu are tried at the edges of block_length_phases equal bins of m (and
// mu = 2), so the chosen block is within a factor 1 + 1 / block_length_phases of the best one by that count.
// The neighbour rule, which raises levels, is not counted.
inline constexpr std::size_t block_length_phases = 64;
// Integers (as doubles, exact to 2^53), so that tallies added in any order, over threads or processes, are
// the same: [block_tally_particles] the moving particles M, [block_tally_steps] the sum of their 2^n_i (1 for
// a step of at least L), [block_tally_shorter + k] that sum over the particles with m_i in bin k, whose steps
// double with a block longer than L / (1 + k / block_length_phases).
inline constexpr std::size_t block_tally_particles = 0;
inline constexpr std::size_t block_tally_steps = 1;
inline constexpr std::size_t block_tally_shorter = 2;
using BlockStepTally = std::array<double, block_tally_shorter + block_length_phases>;
// The tally of the moving (neither fixed nor ejected) particles among the first `count`, for a longest block
// `longest` (s); added to `tally`.
void tally_block_steps(double longest, std::span<const double> time_step, std::span<const std::uint8_t> flags,
                       std::size_t count, BlockStepTally& tally);
// The block length in [longest / 2, longest] with the least work per unit time by `tally` (of the same
// `longest`), a block's passes over all particles counted as `block_work` steps per particle; of equal ones
// the longest.
[[nodiscard]] double cheapest_block_length(double longest, const BlockStepTally& tally, double block_work);

// The levels the neighbour rule reads, indexed like the neighbour lists: in a serial run the schedule's own;
// over several processes those of the owned particles and of the halo copies (their owners' levels), with the
// schedule's particle i at list index i + offset. scheduled[j] == 0: j is not scheduled (fixed or ejected).
struct NeighbourLevels {
  std::span<const std::uint8_t> level;
  std::span<const std::uint8_t> scheduled;
  std::size_t offset = 0;
};

class BlockSchedule {
 public:
  // Starts a block of length `block` for the moving (neither fixed nor ejected) particles among the
  // first `count` (the lists' particles; the rest, ejected, never take part) from their own steps,
  // then raises levels until no particle is more than neighbour_levels() coarser than a neighbour. Throws
  // TimeStepCollapse if a level above block_finest_level_limit is needed (so does relevel()). A neighbour is
  // a list entry within the kernel support (`support`, pair_support.hpp), or any entry without it.
  void start(double block, std::span<const double> time_step, std::span<const std::uint8_t> flags,
             std::size_t count, const NeighbourLists& lists, const PairSupport* support = nullptr);

  [[nodiscard]] bool finished() const { return tick_ == ticks_per_block(); }
  // Advances to the next tick at which some step ends; returns the time from the previous tick, s.
  double advance();
  // The particles whose step ends at the current tick, in index order.
  [[nodiscard]] std::span<const std::uint32_t> active() const { return active_; }
  // The step length of particle i at its current level, s.
  [[nodiscard]] double step_of(std::size_t i) const;
  // Per-particle lengths of the steps that end now (indexed by particle, valid for the active ones; a
  // woken particle's is shorter than its level's), for correct().
  [[nodiscard]] std::span<const double> active_steps() const { return active_steps_; }
  // New levels for the active particles, whose steps just ended, from their new limits; they start
  // their next step at the current tick.
  void relevel(std::span<const double> time_step, const NeighbourLists& lists,
               const PairSupport* support = nullptr);

  // The pieces of start(), advance() and relevel(), for a schedule over several processes, which agree on the
  // finest level and the next tick between them (Simulation does) and read their neighbours' levels through
  // NeighbourLevels.
  //   start() = assign_levels(); raise_levels() until no process changes; begin_ticks(finest over all)
  void assign_levels(double block, std::span<const double> time_step, std::span<const std::uint8_t> flags,
                     std::size_t count);
  // One sweep of the neighbour rule over every scheduled particle, reading `levels` (of the sweep before);
  // true when a level rose.
  bool raise_levels(const NeighbourLists& lists, const PairSupport* support, const NeighbourLevels& levels);
  void begin_ticks(int finest);  // finest >= finest_scheduled_level()
  [[nodiscard]] int finest_scheduled_level() const;
  //   advance() = advance_to(next_end() smallest over all)
  [[nodiscard]] std::uint64_t next_end() const;
  double advance_to(std::uint64_t tick);
  //   relevel() = choose_levels(); apply_levels(largest over all, at least finest_level());
  //               wake(the active particles, at their new levels)
  // choose_levels() returns the largest level chosen (0 when none is active).
  int choose_levels(std::span<const double> time_step, const NeighbourLists& lists,
                    const PairSupport* support, const NeighbourLevels& levels);
  void apply_levels(int finest);
  // Wakes the scheduled particles of this schedule that are neighbours (within the support) of `wakers`
  // (list indices) more than neighbour_levels() levels finer than they are; waker_level[k]: the level
  // of list index k (read for the wakers only).
  void wake(std::span<const std::uint32_t> wakers, std::span<const std::uint8_t> waker_level,
            const NeighbourLists& lists, const PairSupport* support, std::size_t offset);
  // Per particle: its level, and whether it is scheduled (for NeighbourLevels).
  [[nodiscard]] std::span<const std::uint8_t> levels() const { return level_; }
  [[nodiscard]] std::span<const std::uint8_t> scheduled() const { return scheduled_; }

  // How many levels coarser than a neighbour a particle may be (>= 1), from the next start() or
  // assign_levels() on; block_neighbour_levels until set.
  void set_neighbour_levels(int levels);
  [[nodiscard]] int neighbour_levels() const { return neighbour_levels_; }

  [[nodiscard]] double block() const { return block_; }
  // Time from the start of the block to the current tick, s.
  [[nodiscard]] double elapsed() const {
    return block_ * static_cast<double>(tick_) / static_cast<double>(ticks_per_block());
  }
  [[nodiscard]] int finest_level() const { return finest_; }
  [[nodiscard]] std::uint64_t ticks_per_block() const { return std::uint64_t{1} << finest_; }
  // Number of particles at each level at the start of the block (for the log).
  [[nodiscard]] const std::vector<std::size_t>& level_counts() const { return level_counts_; }
  // Bytes held by the per-particle arrays (capacity, as allocated).
  [[nodiscard]] std::size_t bytes() const;

 private:
  void refine_to(int level);  // rescales the ticks so that `level` exists
  [[nodiscard]] NeighbourLevels own_levels() const { return {level_, scheduled_, 0}; }
  [[nodiscard]] int neighbour_floor(std::size_t i, const NeighbourLists& lists, const PairSupport* support,
                                    const NeighbourLevels& levels) const;

  double block_ = 0.0;
  int neighbour_levels_ = block_neighbour_levels;       // of the block under way
  int next_neighbour_levels_ = block_neighbour_levels;  // from the next block on
  int finest_ = 0;
  std::uint64_t tick_ = 0;
  std::vector<std::uint8_t> level_;        // per particle; only moving particles are scheduled
  std::vector<std::uint64_t> start_tick_;  // per particle: tick at which its current step started
  std::vector<std::uint64_t> end_tick_;    // per particle: tick at which its current step ends
  std::vector<std::uint8_t> scheduled_;    // per particle: moving and in the lists
  std::vector<std::uint32_t> active_;      // particles whose step ends at tick_
  std::vector<double> active_steps_;       // per particle: the step of an active particle, s
  std::vector<std::uint8_t> wanted_;       // per active particle: its next level (choose_levels)
  std::vector<std::uint8_t> wake_floor_;   // per particle: the level a waker asks for (wake)
  std::vector<std::uint32_t> woken_;       // the particles with a wake_floor_
  std::vector<std::vector<std::pair<std::uint32_t, std::uint8_t>>> wake_found_;  // per thread: (woken, floor)
  std::vector<std::size_t> level_counts_;
};

}  // namespace craterkit::sph
