#pragma once
// Neighbour lists for SPH with a variable smoothing length.
//
// Pair criterion (symmetric): j is a neighbour of i when |x_i - x_j| < h_i + h_j and j != i, i.e. the
// support of the kernel evaluated at the mean smoothing length hbar = (h_i + h_j)/2 with support 2 hbar.
// With a skin s > 0 the lists hold every pair with |x_i - x_j| < (1 + s)(h_i + h_j): a superset that stays
// valid while particles move and h grows a little (see NeighbourSearch::needs_rebuild); the pair loop then
// sees some pairs beyond the support, where the kernel and its gradient are zero.
//
// Storage: FULL symmetric lists in CSR form (j in list(i) iff i in list(j)), 4 bytes per entry. Full rather
// than half lists because the engine's pair loops gather into particle i only: no atomics, no colouring, and
// a sum order that does not depend on the thread count (bitwise-reproducible runs and restarts). Half lists
// would halve the list memory (about 120 instead of 240 bytes per particle at 60 neighbours) but need
// scattered writes to j. Within list(i) neighbours are ordered along the space-filling curve.
//
// Periodic axes use the minimum-image convention; the box edge along a periodic axis must exceed
// 2 (1 + s)(h_i + h_j) for every pair, so that no pair interacts through two images.
//
// Algorithm: a Morton octree with per-node bounding boxes and maximum h (robust for widely varying h and
// for particles thrown far away), OpenMP-parallel and allocation-free in steady state (buffers are kept
// across rebuilds). A sparse cell list was measured 15-20 % slower, and far slower with a wide spread of
// h, and removed (bench/RESULTS_neighbours.md).
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "craterkit/sph/particles.hpp"

namespace craterkit::sph {

// Simulation box. lower/upper matter only on periodic axes, where positions must lie in [lower, upper)
// (up to one box edge outside is tolerated by displacement(); wrap positions after each drift).
struct Box {
  std::array<double, 3> lower{0.0, 0.0, 0.0};
  std::array<double, 3> upper{0.0, 0.0, 0.0};
  std::array<bool, 3> periodic{false, false, false};

  [[nodiscard]] double edge(int axis) const { return upper[axis] - lower[axis]; }
  [[nodiscard]] bool any_periodic() const { return periodic[0] || periodic[1] || periodic[2]; }
};

// Component `axis` of a separation d = x_i - x_j mapped to the minimum image (identity on open axes).
[[nodiscard]] inline double minimum_image(const Box& box, int axis, double d) noexcept {
  if (!box.periodic[axis]) return d;
  const double edge = box.edge(axis);
  if (d > 0.5 * edge) return d - edge;
  if (d < -0.5 * edge) return d + edge;
  return d;
}

// x_i - x_j with the minimum-image convention: what the rates need for x_ij.
[[nodiscard]] inline std::array<double, 3> displacement(const Box& box, double xi, double yi, double zi,
                                                        double xj, double yj, double zj) noexcept {
  return {minimum_image(box, 0, xi - xj), minimum_image(box, 1, yi - yj), minimum_image(box, 2, zi - zj)};
}
[[nodiscard]] inline std::array<double, 3> displacement(const Box& box, const Particles& particles,
                                                        std::size_t i, std::size_t j) noexcept {
  return displacement(box, particles.x[i], particles.y[i], particles.z[i], particles.x[j], particles.y[j],
                      particles.z[j]);
}

// Maps a coordinate into [lower, upper) along a periodic axis (identity on open axes).
[[nodiscard]] inline double wrap_position(const Box& box, int axis, double v) noexcept {
  if (!box.periodic[axis]) return v;
  const double edge = box.edge(axis);
  v -= edge * std::floor((v - box.lower[axis]) / edge);
  return v < box.upper[axis] ? v : box.lower[axis];  // guards the round-up case v == upper
}

// CSR neighbour lists: the neighbours of i are neighbours[offsets[i] .. offsets[i+1]).
struct NeighbourLists {
  std::vector<std::uint64_t> offsets;     // size n + 1
  std::vector<std::uint32_t> neighbours;  // particle indices

  [[nodiscard]] std::size_t particle_count() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  [[nodiscard]] std::span<const std::uint32_t> of(std::size_t i) const {
    return {neighbours.data() + offsets[i], neighbours.data() + offsets[i + 1]};
  }
  [[nodiscard]] std::size_t count(std::size_t i) const { return offsets[i + 1] - offsets[i]; }
  [[nodiscard]] std::size_t total() const { return offsets.empty() ? 0 : offsets.back(); }
  [[nodiscard]] double mean_neighbours() const {
    return particle_count() ? double(total()) / double(particle_count()) : 0.0;
  }
  // Bytes held (capacity, as allocated).
  [[nodiscard]] std::size_t bytes() const {
    return offsets.capacity() * sizeof(std::uint64_t) + neighbours.capacity() * sizeof(std::uint32_t);
  }
};

struct NeighbourSearchOptions {
  double skin = 0.0;           // relative Verlet skin s >= 0 (lists hold r < (1 + s)(h_i + h_j))
  std::size_t leaf_size = 64;  // octree: maximum particles per leaf (>= 1); 64 measured fastest
};

// What the search reads: positions and smoothing lengths (all the same length, h > 0 and finite).
struct NeighbourInput {
  std::span<const double> x, y, z, smoothing_length;
};
[[nodiscard]] inline NeighbourInput neighbour_input(const Particles& p) {
  return {p.x, p.y, p.z, p.smoothing_length};
}

// Holds the work buffers (sorted copies of positions and h, octree, candidate lists, per-thread overflow)
// between rebuilds, so a rebuild allocates nothing once the particle count and neighbour counts are stable.
class NeighbourSearch {
 public:
  explicit NeighbourSearch(NeighbourSearchOptions options = {});

  // Rebuilds `lists` (its capacity is reused) for the given positions. Throws std::invalid_argument on
  // mismatched sizes, non-positive or non-finite h, bad options, or a periodic box too small for the h.
  void build(const NeighbourInput& input, const Box& box, NeighbourLists& lists);
  [[nodiscard]] NeighbourLists build(const NeighbourInput& input, const Box& box) {
    NeighbourLists lists;
    build(input, box, lists);
    return lists;
  }

  // True when the lists of the last build may miss a pair of the CURRENT positions and h: sufficient
  // criterion, per particle, |x_i - x_i(build)| + max(0, h_i - h_i(build)) > s h_i(build) (then two
  // particles that were >= (1+s)(h_i+h_j) apart at the build may now be < h_i+h_j apart). Always true when
  // s == 0 (unless nothing moved), when nothing was built, or when the particle count changed. Reordering
  // the particles (Particles::permute) invalidates the lists: rebuild after sorting. OpenMP-parallel.
  [[nodiscard]] bool needs_rebuild(const NeighbourInput& input) const;

  // Frees the buffers only a build needs (sort keys, tree, candidates, per-thread scratch: about 40 bytes
  // per particle), keeping what needs_rebuild() reads (sorted copies of positions and h). For runs short of
  // memory: the pair loops then do not hold them; the next build allocates them again.
  void release_workspace();

  [[nodiscard]] const NeighbourSearchOptions& options() const { return options_; }
  // Bytes of the work buffers kept between rebuilds (capacity), excluding the lists themselves.
  [[nodiscard]] std::size_t workspace_bytes() const;

 private:
  struct Group {                         // an octree leaf: a contiguous range of sorted particles
    std::array<double, 3> lower, upper;  // tight bounding box of the particles
    double h_max;
    std::uint32_t begin, end;
  };
  struct Node {  // octree node in depth-first order; leaves point to a group
    std::array<double, 3> lower, upper;
    double h_max;
    std::uint32_t skip;  // index of the next node after this subtree
    std::int32_t group;  // leaf: index into groups_, internal: -1
  };

  void sort_particles(const NeighbourInput& input, const Box& box);
  void make_octree();
  void split_at_median(std::uint32_t begin, std::uint32_t end);
  template <bool Periodic>
  void collect_pairs(const Box& box, NeighbourLists& lists);
  template <bool Periodic>
  void candidates_octree(std::size_t g, const Box& box, std::vector<std::uint32_t>& out) const;

  NeighbourSearchOptions options_;
  bool built_ = false;
  Box box_{};                                                   // box of the last build
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed_;  // (key, original index), sorted
  std::vector<double> xs_, ys_, zs_, hs_;                       // sorted copies (build state)
  std::vector<std::uint32_t> original_;                         // sorted index -> original index
  std::vector<Group> groups_;
  std::vector<Node> nodes_;
  std::vector<std::uint32_t> rank_;      // original index -> sorted index
  std::vector<std::uint32_t> group_of_;  // sorted index -> group
  // Candidate groups of each group (CSR): groups whose box may hold a neighbour of one of its particles.
  std::vector<std::uint64_t> candidate_offsets_;
  std::vector<std::uint32_t> candidates_;
  // Per-thread state of a build: the thread's region of the lists and its overflow vector.
  struct ThreadScratch {
    std::vector<std::uint32_t> found, candidates;  // overflow lists (and sampling scratch); candidates
    std::size_t region_start = 0, region_size = 0, region_used = 0, final_start = 0;
    std::size_t used = 0;           // entries of `found` holding overflow lists
    std::size_t overflow_from = 0;  // first particle whose list went to `found`
  };
  std::vector<ThreadScratch> scratch_;
};

}  // namespace craterkit::sph
