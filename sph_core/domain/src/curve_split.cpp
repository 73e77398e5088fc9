#include "craterkit/sph/domain/curve_split.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace craterkit::sph {

CurveCube global_bounding_cube(std::span<const double> x, std::span<const double> y,
                               std::span<const double> z, const Communicator& comm) {
  if (x.size() != y.size() || x.size() != z.size())
    throw std::invalid_argument("global_bounding_cube: x, y, z must have the same length");
  constexpr double inf = std::numeric_limits<double>::infinity();
  std::vector<double> lower{inf, inf, inf}, upper{-inf, -inf, -inf};
  bool finite = true;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double p[3] = {x[i], y[i], z[i]};
    for (int a = 0; a < 3; ++a) {
      finite = finite && std::isfinite(p[a]);
      lower[std::size_t(a)] = std::min(lower[std::size_t(a)], p[a]);
      upper[std::size_t(a)] = std::max(upper[std::size_t(a)], p[a]);
    }
  }
  if (!comm.all(finite)) throw std::invalid_argument("space-filling curve: non-finite particle coordinate");
  comm.min(lower);
  comm.max(upper);
  if (!(lower[0] <= upper[0])) return {};  // no particle on any rank
  return cube_around({lower[0], lower[1], lower[2]}, {upper[0], upper[1], upper[2]});
}

int KeyRanges::owner(std::uint64_t key) const {
  // The last r with lower[r] <= key.
  const auto above = std::upper_bound(lower.begin(), lower.end() - 1, key);
  return int(above - lower.begin()) - 1;
}

KeyRanges split_by_work(std::span<const std::uint64_t> keys, std::span<const double> work,
                        const Communicator& comm) {
  if (keys.size() != work.size())
    throw std::invalid_argument("split_by_work: one work value per key expected");
  if (!std::is_sorted(keys.begin(), keys.end()))
    throw std::invalid_argument("split_by_work: keys must be sorted");
  // Work below each particle: prefix[i] = work of keys[0..i).
  std::vector<double> prefix(keys.size() + 1, 0.0);
  bool valid = true;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    valid = valid && std::isfinite(work[i]) && work[i] >= 0;
    prefix[i + 1] = prefix[i] + work[i];
  }
  if (!comm.all(valid)) throw std::invalid_argument("split_by_work: work must be finite and >= 0");
  const auto local_work_below = [&](std::uint64_t key) {
    return prefix[std::size_t(std::lower_bound(keys.begin(), keys.end(), key) - keys.begin())];
  };

  const int ranks = comm.size();
  std::vector<double> total{prefix.back()};
  comm.sum(total);
  // Bisection for every split point r = 1..R-1 at once, each in [low, high], which holds the smallest key k
  // with work_below(k) >= r/R of the total. Every rank holds the same low and high (they follow from sums
  // over all ranks), so every rank leaves the loop at the same pass.
  const std::size_t splits = std::size_t(std::max(ranks - 1, 0));
  std::vector<std::uint64_t> low(splits, 0), high(splits, std::uint64_t(1) << 63);
  std::vector<double> below(splits);
  const auto middle = [&](std::size_t s) { return low[s] + (high[s] - low[s]) / 2; };
  for (;;) {
    bool open = false;
    for (std::size_t s = 0; s < splits; ++s) {
      open = open || low[s] < high[s];
      below[s] = low[s] < high[s] ? local_work_below(middle(s)) : 0.0;
    }
    if (!open) break;
    comm.sum(below);
    for (std::size_t s = 0; s < splits; ++s) {
      if (low[s] >= high[s]) continue;
      const double target = total[0] * double(s + 1) / double(ranks);
      if (below[s] < target)
        low[s] = middle(s) + 1;
      else
        high[s] = middle(s);
    }
  }
  KeyRanges ranges;
  ranges.lower.reserve(std::size_t(ranks) + 1);
  ranges.lower.push_back(0);
  for (std::size_t s = 0; s < splits; ++s) ranges.lower.push_back(std::max(low[s], ranges.lower.back()));
  ranges.lower.push_back(std::numeric_limits<std::uint64_t>::max());
  return ranges;
}

}  // namespace craterkit::sph
