#include "craterkit/sph/integration/block_time_steps.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include <omp.h>

#include "craterkit/sph/particles/mirror_image.hpp"

namespace craterkit::sph {

namespace {

// 2^-k for k = 0 ... 64: x 2^-k as a product is exact, as ldexp is, while the result is a normal number, and
// costs a multiplication instead of a library call (the schedule's ldexp calls were about 1 % of an SCI run's
// instructions, bench/RESULTS.md).
constexpr std::array<double, 65> inverse_powers_of_two = [] {
  std::array<double, 65> powers{};
  double power = 1.0;
  for (double& p : powers) {
    p = power;
    power *= 0.5;
  }
  return powers;
}();

// x 2^-k; ldexp where the product could leave the normal range.
inline double scaled_down(double x, int k) {
  constexpr double smallest_exact = 0x1p-950;  // x 2^-64 stays normal above it
  if (k <= 64 && std::abs(x) >= smallest_exact) return x * inverse_powers_of_two[std::size_t(k)];
  return std::ldexp(x, -k);
}

}  // namespace

int block_level(double block, double step) {
  if (std::isnan(step)) return block_finest_level_limit + 1;  // a NaN step is no step: an error
  if (!(step < block)) return 0;                              // also +infinity
  if (!(step > 0.0)) return block_finest_level_limit + 1;
  int level = static_cast<int>(std::ceil(std::log2(block / step)));
  level = std::max(level, 0);
  // log2 may round either way: settle on the smallest level whose step is within the limit.
  while (level > 0 && scaled_down(block, level - 1) <= step) --level;
  while (scaled_down(block, level) > step && level <= block_finest_level_limit) ++level;
  return level;
}

void tally_block_steps(double longest, std::span<const double> time_step, std::span<const std::uint8_t> flags,
                       std::size_t count, BlockStepTally& tally) {
  for (std::size_t i = 0; i < count; ++i) {
    if ((flags[i] & (particle_fixed | particle_ejected)) != 0) continue;
    tally[block_tally_particles] += 1.0;
    const double ratio = longest / time_step[i];
    if (!(ratio > 1.0)) {  // a step at least the block's (or no step: reported by the schedule)
      tally[block_tally_steps] += 1.0;
      continue;
    }
    int exponent = 0;
    const double mantissa = 2.0 * std::frexp(ratio, &exponent);  // ratio = mantissa 2^(exponent - 1)
    const double steps = std::ldexp(1.0, exponent - 1);
    tally[block_tally_steps] += steps;
    if (mantissa == 1.0) continue;  // a power-of-two fraction of the block: never the shorter step
    const auto bin = std::min(block_length_phases - 1,
                              static_cast<std::size_t>((mantissa - 1.0) * double(block_length_phases)));
    tally[block_tally_shorter + bin] += steps;
  }
}

double cheapest_block_length(double longest, const BlockStepTally& tally, double block_work) {
  // mu_j = 1 + j / K: the bins from j on take the shorter step; mu = 2 (j = K): none does.
  const double fixed = tally[block_tally_steps] + block_work * tally[block_tally_particles];
  double shorter = 0.0;
  for (std::size_t k = 0; k < block_length_phases; ++k) shorter += tally[block_tally_shorter + k];
  double best_mu = 1.0;
  double best_work = fixed + shorter;
  for (std::size_t j = 1; j <= block_length_phases; ++j) {
    shorter -= tally[block_tally_shorter + j - 1];
    const double mu = 1.0 + double(j) / double(block_length_phases);
    const double work = mu * (fixed + shorter);
    if (work < best_work) {
      best_work = work;
      best_mu = mu;
    }
  }
  return longest / best_mu;
}

namespace {

[[noreturn]] void throw_collapse(double block, double step, std::size_t particle) {
  char text[160];
  std::snprintf(
      text, sizeof text,
      "time step collapsed: a particle's step %.3g s needs more than %d halvings of the block of %.3g s",
      step, block_finest_level_limit, block);
  throw TimeStepCollapse(text, particle);
}

}  // namespace

std::size_t BlockSchedule::bytes() const {
  std::size_t bytes =
      (level_.capacity() + scheduled_.capacity() + wanted_.capacity() + wake_floor_.capacity());
  bytes += (start_tick_.capacity() + end_tick_.capacity()) * sizeof(std::uint64_t);
  bytes += (active_.capacity() + woken_.capacity()) * sizeof(std::uint32_t);
  bytes += active_steps_.capacity() * sizeof(double);
  for (const auto& found : wake_found_) bytes += found.capacity() * sizeof(found[0]);
  return bytes;
}

void BlockSchedule::set_neighbour_levels(int levels) {
  if (levels < 1) throw std::invalid_argument("block time steps: neighbour levels must be at least 1");
  next_neighbour_levels_ = levels;
}

int BlockSchedule::neighbour_floor(std::size_t i, const NeighbourLists& lists, const PairSupport* support,
                                   const NeighbourLevels& levels) const {
  const std::size_t listed = i + levels.offset;
  int highest = 0;
  for (const std::uint32_t entry : lists.of(listed)) {
    const std::size_t j = neighbour_index(entry);  // a mirror image has its source's level
    if (levels.scheduled[j] == 0 || int(levels.level[j]) <= highest) continue;
    if (support == nullptr || (*support)(listed, entry)) highest = int(levels.level[j]);
  }
  return highest - neighbour_levels_;
}

void BlockSchedule::assign_levels(double block, std::span<const double> time_step,
                                  std::span<const std::uint8_t> flags, std::size_t count) {
  block_ = block;
  neighbour_levels_ = next_neighbour_levels_;
  level_.assign(count, 0);
  end_tick_.assign(count, 0);
  start_tick_.assign(count, 0);
  scheduled_.assign(count, 0);
  active_steps_.assign(count, 0.0);
  wake_floor_.assign(count, 0);
  active_.clear();
  const auto n = static_cast<std::int64_t>(count);
  int bad = -1;
#pragma omp parallel for schedule(static) reduction(max : bad)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if ((flags[i] & (particle_fixed | particle_ejected)) != 0) continue;
    scheduled_[i] = 1;
    const int level = block_level(block, time_step[i]);
    if (level > block_finest_level_limit) bad = std::max(bad, int(i));
    level_[i] = static_cast<std::uint8_t>(std::min(level, block_finest_level_limit));
  }
  if (bad >= 0) throw_collapse(block, time_step[std::size_t(bad)], std::size_t(bad));
}

bool BlockSchedule::raise_levels(const NeighbourLists& lists, const PairSupport* support,
                                 const NeighbourLevels& levels) {
  // Each sweep reads the levels of the sweep before, so the result does not depend on the thread count.
  const auto n = static_cast<std::int64_t>(level_.size());
  std::vector<std::uint8_t> raised(level_.size());
  bool changed = false;
#pragma omp parallel for schedule(dynamic, 256) reduction(|| : changed)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    raised[i] = level_[i];
    if (scheduled_[i] == 0) continue;
    const int floor = neighbour_floor(i, lists, support, levels);
    if (floor > int(level_[i])) {
      raised[i] = static_cast<std::uint8_t>(floor);
      changed = true;
    }
  }
  level_.swap(raised);
  return changed;
}

int BlockSchedule::finest_scheduled_level() const {
  int finest = 0;
  for (std::size_t i = 0; i < level_.size(); ++i) {
    if (scheduled_[i] != 0) finest = std::max(finest, int(level_[i]));
  }
  return finest;
}

void BlockSchedule::begin_ticks(int finest) {
  finest_ = finest;
  level_counts_.assign(std::size_t(finest_) + 1, 0);
  for (std::size_t i = 0; i < level_.size(); ++i) {
    if (scheduled_[i] == 0) continue;
    ++level_counts_[level_[i]];
    start_tick_[i] = 0;
    end_tick_[i] = std::uint64_t{1} << (finest_ - level_[i]);
  }
  tick_ = 0;
}

void BlockSchedule::start(double block, std::span<const double> time_step,
                          std::span<const std::uint8_t> flags, std::size_t count, const NeighbourLists& lists,
                          const PairSupport* support) {
  assign_levels(block, time_step, flags, count);
  // Neighbour rule: until no particle is more than two levels coarser than a neighbour.
  while (raise_levels(lists, support, own_levels())) {
  }
  begin_ticks(finest_scheduled_level());
}

std::uint64_t BlockSchedule::next_end() const {
  const auto n = static_cast<std::int64_t>(level_.size());
  std::uint64_t next = ticks_per_block();
#pragma omp parallel for schedule(static) reduction(min : next)
  for (std::int64_t ii = 0; ii < n; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    if (scheduled_[i] != 0) next = std::min(next, end_tick_[i]);
  }
  return next;
}

double BlockSchedule::advance_to(std::uint64_t next) {
  active_.clear();
  for (std::size_t i = 0; i < level_.size(); ++i) {
    if (scheduled_[i] != 0 && end_tick_[i] == next) {
      active_.push_back(static_cast<std::uint32_t>(i));
      // The step that ends here: 2^(F - level) ticks, or fewer when it was cut short by a neighbour.
      active_steps_[i] = scaled_down(block_ * static_cast<double>(end_tick_[i] - start_tick_[i]), finest_);
    }
  }
  const double dt = scaled_down(block_ * static_cast<double>(next - tick_), finest_);
  tick_ = next;
  return dt;
}

double BlockSchedule::advance() {
  return advance_to(next_end());
}

double BlockSchedule::step_of(std::size_t i) const {
  return scaled_down(block_, int(level_[i]));
}

void BlockSchedule::refine_to(int level) {
  if (level <= finest_) return;
  const int shift = level - finest_;
  for (std::size_t i = 0; i < end_tick_.size(); ++i) {
    end_tick_[i] <<= shift;
    start_tick_[i] <<= shift;
  }
  tick_ <<= shift;
  finest_ = level;
}

int BlockSchedule::choose_levels(std::span<const double> time_step, const NeighbourLists& lists,
                                 const PairSupport* support, const NeighbourLevels& levels) {
  const auto n = static_cast<std::int64_t>(active_.size());
  wanted_.resize(active_.size());
  int highest = 0, bad = -1;
#pragma omp parallel for schedule(static) reduction(max : highest, bad)
  for (std::int64_t kk = 0; kk < n; ++kk) {
    const auto k = static_cast<std::size_t>(kk);
    const std::size_t i = active_[k];
    const int current = level_[i];
    // No neighbour is finer than finest_ (every process's levels are within the agreed finest level), so a
    // particle that wants finest_ - neighbour_levels_ or finer for itself needs no look at them: in the
    // substeps of the finest level, the most frequent, that is most of the active particles (in the shock
    // stage).
    const int own = block_level(block_, time_step[i]);
    int want =
        own >= finest_ - neighbour_levels_ ? own : std::max(own, neighbour_floor(i, lists, support, levels));
    if (want > block_finest_level_limit) bad = std::max(bad, int(i));
    want = std::min(want, block_finest_level_limit);
    int level = current;
    if (want > current) {
      level = want;  // always aligned: the step that just ended was
    } else if (want < current) {
      const int coarser = current - 1;  // one level at a time, where the longer step is aligned
      const std::uint64_t coarser_ticks = std::uint64_t{1} << (finest_ - coarser);
      if (tick_ % coarser_ticks == 0 && tick_ < ticks_per_block()) level = coarser;
    }
    wanted_[k] = static_cast<std::uint8_t>(level);
    highest = std::max(highest, level);
  }
  if (bad >= 0) throw_collapse(block_, time_step[std::size_t(bad)], std::size_t(bad));
  return highest;
}

void BlockSchedule::apply_levels(int finest) {
  refine_to(finest);
  for (std::size_t k = 0; k < active_.size(); ++k) {
    const std::size_t i = active_[k];
    level_[i] = wanted_[k];
    start_tick_[i] = tick_;
    end_tick_[i] = tick_ + (std::uint64_t{1} << (finest_ - level_[i]));
  }
}

void BlockSchedule::wake(std::span<const std::uint32_t> wakers, std::span<const std::uint8_t> waker_level,
                         const NeighbourLists& lists, const PairSupport* support, std::size_t offset) {
  // Waking (Saitoh & Makino 2009): a neighbour in the middle of a step more than two levels coarser than
  // a waker's new level has its step cut short at the next tick aligned to the level two coarser than
  // that, and continues at that level. Of several wakers the finest decides. Each thread lists the
  // (neighbour, floor) pairs of a contiguous run of the wakers; the runs are then read in order, as one
  // loop over the wakers would read them.
  const std::size_t count = wakers.size();
  if (wake_found_.size() < std::size_t(omp_get_max_threads()))
    wake_found_.resize(std::size_t(omp_get_max_threads()));
  std::size_t threads = 1;
#pragma omp parallel if (count > 256)
  {
#pragma omp single
    threads = std::size_t(omp_get_num_threads());
    const auto id = std::size_t(omp_get_thread_num());
    std::vector<std::pair<std::uint32_t, std::uint8_t>>& found = wake_found_[id];
    found.clear();
    const std::size_t first = count * id / std::size_t(omp_get_num_threads());
    const std::size_t last = count * (id + 1) / std::size_t(omp_get_num_threads());
    for (std::size_t w = first; w < last; ++w) {
      const std::uint32_t k = wakers[w];
      const int floor = int(waker_level[k]) - neighbour_levels_;
      if (floor <= 0) continue;
      for (const std::uint32_t entry : lists.of(k)) {
        const std::size_t listed = neighbour_index(entry);
        if (listed < offset || listed - offset >= level_.size()) continue;  // another process's particle
        const std::size_t j = listed - offset;
        if (scheduled_[j] == 0 || int(level_[j]) >= floor || end_tick_[j] <= tick_) continue;
        if (support != nullptr && !(*support)(k, entry)) continue;
        found.emplace_back(std::uint32_t(j), std::uint8_t(floor));
      }
    }
  }
  woken_.clear();
  for (std::size_t t = 0; t < threads; ++t) {
    for (const auto& [j, floor] : wake_found_[t]) {
      if (wake_floor_[j] == 0) woken_.push_back(j);
      wake_floor_[j] = std::max(wake_floor_[j], floor);
    }
  }
  for (const std::uint32_t j : woken_) {
    const int floor = wake_floor_[j];
    wake_floor_[j] = 0;
    const std::uint64_t step = std::uint64_t{1} << (finest_ - floor);
    const std::uint64_t end = (tick_ / step + 1) * step;
    if (end < end_tick_[j]) end_tick_[j] = end;
    level_[j] = static_cast<std::uint8_t>(floor);
  }
}

void BlockSchedule::relevel(std::span<const double> time_step, const NeighbourLists& lists,
                            const PairSupport* support) {
  const int highest = choose_levels(time_step, lists, support, own_levels());
  apply_levels(std::max(highest, finest_));
  wake(active_, level_, lists, support, 0);
}

}  // namespace craterkit::sph
