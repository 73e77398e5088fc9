#pragma once
// Splitting the particles of a distributed run among the ranks along the space-filling curve the engine
// already sorts by (space_filling_curve.hpp): rank r owns the particles whose Morton key lies in
// [lower[r], lower[r + 1]), so that each rank holds a compact piece of space and its particles stay sorted
// along the curve. The split points are chosen so that every rank gets the same share of the measured work
// (pair interactions per particle, or any per-particle cost), not the same number of particles: an impact's
// graded target has its finest, most expensive particles in a small core (docs/parallel.md).
#include <cstdint>
#include <span>
#include <vector>

#include "craterkit/sph/domain/communicator.hpp"
#include "craterkit/sph/particles/space_filling_curve.hpp"

namespace craterkit::sph {

// The cube of bounding_cube() over the points of all ranks together: every rank's keys are keys of one curve,
// equal to those of a serial run over the same points. Collective. Throws std::invalid_argument on every rank
// if any rank holds a non-finite coordinate.
[[nodiscard]] CurveCube global_bounding_cube(std::span<const double> x, std::span<const double> y,
                                             std::span<const double> z, const Communicator& comm);

// Rank r owns keys in [lower[r], lower[r + 1]); lower.front() == 0 and lower.back() == UINT64_MAX (Morton
// keys have 63 bits, so every key has an owner).
struct KeyRanges {
  std::vector<std::uint64_t> lower;

  [[nodiscard]] int ranks() const { return int(lower.size()) - 1; }
  [[nodiscard]] int owner(std::uint64_t key) const;
};

// Split points with equal work per rank: lower[r] is the smallest key k such that the work of all particles
// with keys below k is at least r/R of the total. `keys` (sorted ascending) and `work` (>= 0, finite) are
// this rank's particles; the result is the same on every rank. Found by bisection on the key for all split
// points at once, one sum over the ranks per bit (63), so the split is exact to one key: particles with equal
// keys stay together, and a rank's share differs from the mean by at most the largest work of one key.
// Collective.
[[nodiscard]] KeyRanges split_by_work(std::span<const std::uint64_t> keys, std::span<const double> work,
                                      const Communicator& comm);

}  // namespace craterkit::sph
