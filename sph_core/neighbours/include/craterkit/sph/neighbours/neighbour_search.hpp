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
// scattered writes to j. Within list(i) neighbours are ordered along the space-filling curve (build()) or by
// entry (update()).
//
// Periodic axes use the minimum-image convention; the box edge along a periodic axis must exceed
// 2 (1 + s)(h_i + h_j) for every pair, so that no pair interacts through two images.
//
// Mirror axes (Box::mirror, mirror_image.hpp): a symmetry plane at lower[a]. The search adds, for every
// particle within reach of the plane, its reflection (same h) to the sorted copies it searches, so that
// the lists of the real particles hold the images within (1 + s)(h_i + h_j) like ordinary neighbours, as
// entries with image bits (index | bit 29 + a). Near two planes a particle also gets its corner image
// (both axes). Only the real particles are queried; a particle near a plane lists its own image. Lists
// stay symmetric in the mirrored sense: image_A(j) in list(i) iff image_A(i) in list(j) (a reflection
// is an isometry). At most 2^29 particles (max_search_particles), with or without mirrors.
//
// Algorithm: a Morton octree with per-node bounding boxes and maximum h (robust for widely varying h and
// for particles thrown far away), OpenMP-parallel and allocation-free in steady state (buffers are kept
// across rebuilds; update() frees the few that only its restructures read, see there). A sparse cell list was
// measured 15-20 % slower, and far slower with a wide spread of h, and removed (bench/RESULTS_neighbours.md).
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "craterkit/sph/particles/box.hpp"
#include "craterkit/sph/particles/mirror_image.hpp"
#include "craterkit/sph/particles/particles.hpp"

namespace craterkit::sph {

// Neighbour lists: the neighbours of i are neighbours[offsets[i] .. end(i)). Packed (CSR, as build() writes
// them): `ends` is empty and list i ends where list i + 1 starts. Kept (update() for block time steps): each
// list has a slot with room to grow, list i ends at ends[i], and a slot may have moved to the end of the
// array, so offsets[i + 1] says nothing about list i.
struct NeighbourLists {
  std::vector<std::uint64_t> offsets;     // size n + 1
  std::vector<std::uint64_t> ends;        // empty (packed) or size n
  std::vector<std::uint32_t> neighbours;  // entries: particle index | mirror-image bits (mirror_image.hpp)

  [[nodiscard]] std::size_t particle_count() const { return offsets.empty() ? 0 : offsets.size() - 1; }
  [[nodiscard]] std::uint64_t end(std::size_t i) const { return ends.empty() ? offsets[i + 1] : ends[i]; }
  [[nodiscard]] std::span<const std::uint32_t> of(std::size_t i) const {
    return {neighbours.data() + offsets[i], neighbours.data() + end(i)};
  }
  [[nodiscard]] std::size_t count(std::size_t i) const { return end(i) - offsets[i]; }
  [[nodiscard]] std::size_t total() const {
    if (ends.empty()) return offsets.empty() ? 0 : offsets.back();
    std::size_t sum = 0;
    for (std::size_t i = 0; i < ends.size(); ++i) sum += count(i);
    return sum;
  }
  [[nodiscard]] double mean_neighbours() const {
    return particle_count() ? double(total()) / double(particle_count()) : 0.0;
  }
  // Bytes held (capacity, as allocated).
  [[nodiscard]] std::size_t bytes() const {
    return (offsets.capacity() + ends.capacity()) * sizeof(std::uint64_t) +
           neighbours.capacity() * sizeof(std::uint32_t);
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
// update() is the exception: after a restructure it frees the sort keys, the sorted index -> group map and
// the candidate groups, which the calls until the next restructure do not read (about 36 bytes per particle
// on the SCI example), and the next restructure allocates them again.
class NeighbourSearch {
 public:
  explicit NeighbourSearch(NeighbourSearchOptions options = {});

  // Rebuilds `lists` (its capacity is reused) for the given positions. Throws std::invalid_argument on
  // mismatched sizes, more than max_search_particles, non-positive or non-finite h, bad options, a
  // periodic box too small for the h, or an axis both periodic and mirrored (or mirrored at a non-finite
  // plane).
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
  // With mirrors the criterion still holds: an image moves with its source (a reflection preserves
  // distances, so it moves exactly as far, and it has the same h), and an image left out of the build was
  // at least (1 + s)(h_i + h_j) from every particle i, as any unlisted pair (see add_mirror_images).
  [[nodiscard]] bool needs_rebuild(const NeighbourInput& input) const;

  // Block time steps (block_time_steps.hpp): lists of every particle with the skin, kept from call to call.
  // Each particle has an anchor, its position and h when its list was last searched; the lists hold every
  // pair whose anchors are within (1 + s)(H_i + H_j). A call searches afresh only the particles that moved
  // more than s H since their anchor (|x - X| + max(0, h - H) > s H; then no pair can have come within
  // h_i + h_j unlisted, by the triangle inequality), re-anchors them, and adds each to the lists of its new
  // neighbours. The octree is built over the anchors and refit when some move; it is rebuilt afresh (all
  // particles re-anchored) with `restructure`, when the count or box changed, when a re-anchored particle
  // would need a mirror image the build did not make or has outgrown (1 + s) times the build's largest h, and
  // when moved slots have left too much of the array unused. Each list is sorted by entry, so that a pair
  // loop that skips the pairs beyond h_i + h_j sums the same terms in the same order whatever superset it was
  // given: results do not depend on when the lists were searched (restarts, checkpoints). Throws as build().
  void update(const NeighbourInput& input, const Box& box, NeighbourLists& lists, bool restructure);
  // update() without a restructure, checking only `candidates` (ascending): every other particle is known to
  // be within its anchor's skin (a bound on its motion, room()), and its position is not read. Returns
  // false, changing nothing, when a restructure is due: then call update() with every particle's present
  // position and h.
  bool update_moved(const NeighbourInput& input, const Box& box, NeighbourLists& lists,
                    std::span<const std::uint32_t> candidates);
  // The particles the last update() or update_moved() found beyond their skins and searched afresh, ascending
  // (meaningful when it did not restructure; empty after update_moved() declined).
  [[nodiscard]] std::span<const std::uint32_t> moved() const { return moved_list_; }
  // How far particle i, at (x, y, z) with smoothing length h, is from leaving its anchor's skin: s H - |x -
  // X|
  // - max(0, h - H) (m; negative when it has left).
  [[nodiscard]] double room(std::size_t i, double x, double y, double z, double h, const Box& box) const;
  // Particles leaving the search (ejecta), without a search: `order` is the permutation the particles went
  // through (new index k holds old particle order[k]), of which the first `kept` stay, in increasing old
  // index. The lists of update() lose the entries of the particles that left and are renumbered; a list's
  // entries keep their order (the renumbering is monotone), so the next update() and every pair loop see
  // what they would after a restructure (update()). The leavers' anchors stay in the tree, marked, and
  // are never listed again. Returns false, changing nothing, when the lists are not update()'s or `order`
  // is not such a permutation of the search's particles: then build or restructure.
  bool remove_particles(std::span<const std::uint32_t> order, std::size_t kept, NeighbourLists& lists);
  // Octree builds by update() (each re-anchors every particle).
  [[nodiscard]] std::uint64_t restructures() const { return restructures_; }
  // Particle lists searched by update() (all particles at a restructure, the moved ones otherwise).
  [[nodiscard]] std::uint64_t searches() const { return searches_; }

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

  void sort_particles(const NeighbourInput& input, const Box& box, bool kept_lists);
  void add_mirror_images(const NeighbourInput& input, const Box& box, double h_max, double margin);
  void make_octree();
  void split_at_median(std::uint32_t begin, std::uint32_t end);
  // Lists of every real particle with pairs r < grow (h_i + h_j), in three steps: index_sorted_particles
  // (rank_, group_of_), find_candidate_groups (candidate_offsets_, candidates_), write_lists.
  template <bool Periodic>
  void collect_pairs(const Box& box, NeighbourLists& lists, double grow);
  void index_sorted_particles();
  template <bool Periodic>
  void find_candidate_groups(const Box& box, double grow);
  // What the list of one particle needs besides the tree and the candidate groups.
  struct GatherQuery {
    std::array<double, 3> edge, half;  // box edges; half of them on periodic axes, +infinity on the others
    std::array<bool, 3> periodic;
    double grow;
  };
  template <bool Periodic>
  void write_lists(const GatherQuery& query, NeighbourLists& lists);
  // write_lists' parts: the list of sorted particle k into out[0, room) (room + 1 when it may not fit) or
  // into a growable vector from `at`; the threads' regions of the lists laid out before they are filled
  // and joined after.
  template <bool Periodic>
  std::size_t gather_neighbours(std::uint32_t k, std::uint32_t* out, std::size_t room,
                                const GatherQuery& query) const;
  template <bool Periodic>
  std::size_t gather_neighbours_into(std::uint32_t k, std::vector<std::uint32_t>& v, std::size_t at,
                                     const GatherQuery& query) const;
  void lay_out_regions(std::size_t threads, NeighbourLists& lists);
  void join_regions(std::size_t threads, bool overflowed, NeighbourLists& lists);
  template <bool Periodic>
  void candidates_octree(std::size_t g, const Box& box, std::vector<std::uint32_t>& out, double grow) const;
  // update()'s parts: a whole new build into slotted, sorted lists; the particles that moved beyond their
  // anchor's skin (false when one needs a restructure); their new anchors into the tree; one point query.
  void restructure(const NeighbourInput& input, const Box& box, NeighbourLists& lists);
  [[nodiscard]] bool keeps_layout(const NeighbourInput& input, const Box& box,
                                  const NeighbourLists& lists) const;
  bool find_moved(const NeighbourInput& input, const Box& box, std::span<const std::uint32_t> candidates,
                  bool every_particle);
  void search_moved(const Box& box, NeighbourLists& lists);
  void move_anchors(const Box& box);
  void refit_boxes();
  template <bool Periodic>
  void search_anchor(std::uint32_t i, const Box& box, std::vector<std::uint32_t>& out) const;
  void write_moved_lists(NeighbourLists& lists);
  void release_build_buffers();  // what only the collection of the lists reads (restructure())
  void insert_entry(NeighbourLists& lists, std::size_t j, std::uint32_t entry);
  void move_slot(NeighbourLists& lists, std::size_t i, std::size_t room);

  NeighbourSearchOptions options_;
  bool built_ = false;
  Box box_{};                  // box of the last build
  std::size_t particles_ = 0;  // real particles of the last build; the sorted copies also hold images
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed_;  // (key, entry), sorted
  std::vector<double> xs_, ys_, zs_, hs_;  // sorted copies of particles and images (build state)
  std::vector<std::uint32_t> original_;    // sorted index -> entry (original index | image bits)
  std::vector<Group> groups_;
  std::vector<Node> nodes_;
  std::vector<std::uint8_t> group_queried_;  // the group holds a real particle (images are not queried)
  std::vector<std::uint32_t> rank_;          // original index -> sorted index (real particles)
  std::vector<std::uint32_t> group_of_;      // sorted index -> group
  // Mirror boxes only: per particle the axes whose plane it is within reach of (bit a), and where its
  // images start among the image entries (prefix sums, size n + 1; at most 7 x 2^29 < 2^32).
  std::vector<std::uint8_t> near_planes_;
  std::vector<std::uint32_t> image_start_;
  // Candidate groups of each group (CSR): groups whose box may hold a neighbour of one of its particles.
  std::vector<std::uint64_t> candidate_offsets_;
  std::vector<std::uint32_t> candidates_;
  // Per-thread state of a build: the thread's region of the lists and its overflow vector.
  struct ThreadScratch {
    std::vector<std::uint32_t> found, candidates;  // overflow lists (and sampling scratch); candidates
    std::vector<std::uint32_t> movers;             // find_moved: the thread's particles beyond the skin
    std::size_t region_start = 0, region_size = 0, region_used = 0, final_start = 0;
    std::size_t used = 0;           // entries of `found` holding overflow lists
    std::size_t overflow_from = 0;  // first particle whose list went to `found`
  };
  std::vector<ThreadScratch> scratch_;
  // update() only.
  bool kept_ = false;               // the lists are update()'s (slotted, anchored)
  double build_h_max_ = 0.0;        // the largest h of the build (image reach, periodic edge)
  std::array<double, 3> beyond_{};  // how far the deepest particle of the build had crossed each plane
  std::uint64_t restructures_ = 0, searches_ = 0;
  std::vector<std::uint32_t> image_rank_;    // sorted index of each image entry (image_start_ order)
  std::vector<std::uint64_t> slot_end_;      // end of each particle's slot in NeighbourLists::neighbours
  std::uint64_t unused_ = 0;                 // entries of abandoned slots (moved to the end)
  std::vector<std::uint8_t> moved_;          // per particle: re-anchored in this call
  std::vector<std::uint32_t> moved_list_;    // their indices, ascending
  std::vector<std::uint8_t> group_dirty_;    // per group: holds a moved anchor (move_anchors, refit_boxes)
  std::vector<std::uint32_t> dirty_groups_;  // those groups
  // remove_particles(): per sorted entry, 1 when its particle has left (empty when none has since the last
  // build).
  std::vector<std::uint8_t> removed_;
  std::vector<std::array<double, 4>> moved_anchor_;  // their new anchors (x, y, z wrapped; h)
  // Their new lists, in moved_list_ order: spans into the searching thread's scratch `found`.
  std::vector<std::span<const std::uint32_t>> fresh_;
  std::vector<std::uint64_t> fresh_start_;  // where each starts in its thread's buffer
};

}  // namespace craterkit::sph
