#include "craterkit/sph/neighbours/neighbour_search.hpp"

#include <omp.h>

#include <algorithm>
#include <bit>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "craterkit/sph/particles/space_filling_curve.hpp"

namespace craterkit::sph {

namespace {

// Candidates are tested in blocks of this many particles (the size of the stack array of test results;
// the default octree leaf fits in one). Finer blocks of 8 with their own bounding boxes cut the distance
// tests by a quarter but cost more in mispredicted box tests: measured slower (RESULTS_neighbours.md).
constexpr std::uint32_t block_size = 64;

// Gap between the intervals [a0, a1] and [b0, b1] (0 when they overlap), along a periodic axis of
// length `edge` also between their images one edge apart. Called three times per (particle, candidate
// box) pair: forced inline and written with two-argument max/min, which compile to single instructions
// (the initializer-list forms did not inline and cost 11 % of a Sedov step, bench/RESULTS.md).
template <bool Periodic>
[[gnu::always_inline]] inline double interval_gap(double a0, double a1, double b0, double b1,
                                                  bool periodic_axis, double edge) {
  double gap = std::max(0.0, std::max(b0 - a1, a0 - b1));
  if constexpr (Periodic) {
    if (periodic_axis && gap > 0) {
      const double above = std::max(0.0, std::max(b0 + edge - a1, a0 - b1 - edge));
      const double below = std::max(0.0, std::max(b0 - edge - a1, a0 - b1 + edge));
      gap = std::min(gap, std::min(above, below));
    }
  }
  return gap;
}

// Room to grow of a kept list's slot (update(): moved particles add themselves to the lists of their new
// neighbours): an eighth of the list and two entries. Every particle holds its room through all substeps,
// while inserts are few between restructures (at least every sort interval); a list that outgrows its slot
// moves to the end of the array. A quarter and four entries cost about 60 bytes per particle more on the SCI
// example (bench/RESULTS.md).
constexpr std::uint64_t slot_room(std::uint64_t count) {
  return count / 8 + 2;
}

// Resizes a build buffer to `size` without letting std::vector double its capacity (resize alone would:
// with mirror images the buffers first hold the n particles, then n plus the images). `slack` extra
// capacity absorbs the small changes of the image count between builds without reallocating each time.
template <class T>
void resize_buffer(std::vector<T>& v, std::size_t size, std::size_t slack) {
  if (v.capacity() < size) v.reserve(size + slack);
  v.resize(size);
}

}  // namespace

NeighbourSearch::NeighbourSearch(NeighbourSearchOptions options) : options_(options) {
  if (!(options_.skin >= 0.0) || !std::isfinite(options_.skin)) {
    throw std::invalid_argument("neighbour search: skin must be finite and >= 0, got " +
                                std::to_string(options_.skin));
  }
  if (options_.leaf_size < 1 || options_.leaf_size > 4096) {
    throw std::invalid_argument("neighbour search: leaf_size must be in [1, 4096], got " +
                                std::to_string(options_.leaf_size));
  }
}

std::size_t NeighbourSearch::workspace_bytes() const {
  std::size_t bytes =
      keyed_.capacity() * sizeof(keyed_[0]) +
      (xs_.capacity() + ys_.capacity() + zs_.capacity() + hs_.capacity()) * sizeof(double) +
      original_.capacity() * sizeof(std::uint32_t) + groups_.capacity() * sizeof(Group) +
      nodes_.capacity() * sizeof(Node) +
      (rank_.capacity() + group_of_.capacity() + candidates_.capacity()) * sizeof(std::uint32_t) +
      candidate_offsets_.capacity() * sizeof(std::uint64_t) +
      image_start_.capacity() * sizeof(std::uint32_t) + group_queried_.capacity() + near_planes_.capacity() +
      image_rank_.capacity() * sizeof(std::uint32_t) + slot_end_.capacity() * sizeof(std::uint64_t) +
      removed_.capacity() + moved_.capacity() + moved_list_.capacity() * sizeof(std::uint32_t) +
      group_dirty_.capacity() + dirty_groups_.capacity() * sizeof(std::uint32_t) +
      moved_anchor_.capacity() * sizeof(moved_anchor_[0]) + fresh_start_.capacity() * sizeof(std::uint64_t) +
      fresh_.capacity() * sizeof(fresh_[0]);
  for (const auto& t : scratch_)
    bytes += (t.found.capacity() + t.candidates.capacity() + t.movers.capacity()) * sizeof(std::uint32_t);
  return bytes;
}

void NeighbourSearch::release_build_buffers() {
  const auto release = [](auto& v) { std::remove_reference_t<decltype(v)>().swap(v); };
  release(keyed_);
  release(group_of_);
  release(candidate_offsets_);
  release(candidates_);
}

void NeighbourSearch::release_workspace() {
  kept_ = false;  // update() then restructures
  const auto release = [](auto& v) { std::remove_reference_t<decltype(v)>().swap(v); };
  release(keyed_);
  release(groups_);
  release(nodes_);
  release(rank_);
  release(group_of_);
  release(candidate_offsets_);
  release(candidates_);
  release(scratch_);
  release(group_queried_);
  release(near_planes_);
  release(image_start_);
  release(moved_list_);
  release(group_dirty_);
  release(dirty_groups_);
  release(moved_anchor_);
  release(fresh_start_);
  release(fresh_);
}

void NeighbourSearch::sort_particles(const NeighbourInput& in, const Box& box, bool kept_lists) {
  const std::size_t n = in.x.size();
  removed_.clear();
  if (in.y.size() != n || in.z.size() != n || in.smoothing_length.size() != n) {
    throw std::invalid_argument("neighbour search: x, y, z and smoothing_length must have the same length");
  }
  if (n > max_search_particles) {
    throw std::invalid_argument("neighbour search: " + std::to_string(n) +
                                " particles, more than 2^29 (list entries keep 3 bits for mirror images)");
  }
  for (int a = 0; a < 3; ++a) {
    if (box.periodic[a] && !(box.edge(a) > 0 && std::isfinite(box.edge(a)))) {
      throw std::invalid_argument("neighbour search: periodic axis " + std::to_string(a) +
                                  " needs upper > lower, got edge " + std::to_string(box.edge(a)));
    }
    if (box.mirror[a] && box.periodic[a]) {
      throw std::invalid_argument("neighbour search: axis " + std::to_string(a) +
                                  " cannot be both periodic and mirrored");
    }
    if (box.mirror[a] && !std::isfinite(box.lower[a])) {
      throw std::invalid_argument("neighbour search: the mirror plane of axis " + std::to_string(a) +
                                  " (lower = " + std::to_string(box.lower[a]) + ") must be finite");
    }
  }
  particles_ = n;
  xs_.resize(n);
  ys_.resize(n);
  zs_.resize(n);
  keyed_.resize(n);

  // Wrapped positions (periodic axes) into the sorted-copy arrays, unsorted for now; h_max and validity.
  double h_max = 0.0;
  double h_min = std::numeric_limits<double>::infinity();
  bool h_valid = true;
#pragma omp parallel for schedule(static) reduction(max : h_max) reduction(min : h_min) reduction(&& : h_valid)
  for (std::size_t i = 0; i < n; ++i) {
    xs_[i] = wrap_position(box, 0, in.x[i]);
    ys_[i] = wrap_position(box, 1, in.y[i]);
    zs_[i] = wrap_position(box, 2, in.z[i]);
    keyed_[i].second = static_cast<std::uint32_t>(i);  // the list entry of a particle: its index
    const double h = in.smoothing_length[i];
    h_max = std::max(h_max, h);
    h_min = std::min(h_min, h);
    h_valid = h_valid && h > 0 && std::isfinite(h);  // also false for NaN, which min/max ignore
  }
  if (!h_valid) {
    throw std::invalid_argument("neighbour search: smoothing lengths must be finite and > 0 (min " +
                                std::to_string(h_min) + ", max " + std::to_string(h_max) + ")");
  }
  const double reach = 2.0 * h_max * (1.0 + options_.skin);  // largest pair distance in the lists
  for (int a = 0; a < 3; ++a) {
    if (box.periodic[a] && !(box.edge(a) > 2.0 * reach)) {
      throw std::invalid_argument("neighbour search: periodic box edge along axis " + std::to_string(a) +
                                  " (" + std::to_string(box.edge(a)) +
                                  ") must exceed 2 (1 + skin) (h_i + h_j) = " + std::to_string(2.0 * reach) +
                                  " (skin " + std::to_string(options_.skin) +
                                  "; a smaller [neighbours] skin, down to 0, allows a narrower box)");
    }
  }
  // Kept lists (update()) let h grow by the skin before a restructure: the images are made for that h, and
  // find_moved restructures only beyond it (periodic boxes too small for it keep h_max). Their image bands
  // are also widened by a margin (add_mirror_images).
  build_h_max_ = h_max;
  double image_margin = 0.0;
  if (kept_lists) {
    const double grown = h_max * (1.0 + options_.skin);
    bool fits = true;
    for (int a = 0; a < 3; ++a)
      fits = fits && (!box.periodic[a] || box.edge(a) > 4.0 * grown * (1.0 + options_.skin));
    if (fits) build_h_max_ = grown;
    image_margin = options_.skin * build_h_max_;
  }
  if (box.any_mirror()) add_mirror_images(in, box, build_h_max_, image_margin);  // after the n particles
  const std::size_t entries = xs_.size();
  const std::size_t slack = (entries - n) / 4;  // 0 without mirrors
  resize_buffer(hs_, entries, slack);
  resize_buffer(original_, entries, slack);
  const CurveCube cube = bounding_cube(xs_, ys_, zs_);  // also rejects non-finite positions

  // The keys of curve_order(): particles sorted by the engine are found sorted and not re-sorted (without
  // mirrors; with mirrors the images change the cube and the order is sorted afresh).
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < entries; ++k) keyed_[k].first = morton_key(cube, xs_[k], ys_[k], zs_[k]);
  sort_keyed_indices(keyed_);

  // Sorted copies, recomputed from the input in sorted order (no scratch array needed); images reflected
  // exactly as the pair loops reflect them (MirrorImage::position), so both see the same distances.
  const MirrorPlanes planes = mirror_planes(box);
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < entries; ++k) {
    const std::uint32_t entry = keyed_[k].second;
    const MirrorImage image = mirror_image(entry);
    const std::size_t i = image.index;
    original_[k] = entry;
    xs_[k] = image.position(0, planes, wrap_position(box, 0, in.x[i]));
    ys_[k] = image.position(1, planes, wrap_position(box, 1, in.y[i]));
    zs_[k] = image.position(2, planes, wrap_position(box, 2, in.z[i]));
    hs_[k] = in.smoothing_length[i];
  }
}

// Which particles get images: i within reach of the plane of mirrored axis a, i.e. x_a - L_a <
// (1 + s)(h_i + h_max) + beyond_a, where beyond_a >= 0 is how far the deepest particle has crossed that
// plane (normally 0: particles stay on their side; for kept lists the deepest crossing plus the margin, and
// the band is wider by the margin still, so that find_moved's test of the same form has room on both
// sides). Exact: for j not imaged along a and any particle i,
// the image distance along a is |(x_i - L) + (x_j - L)| >= -beyond_a + (1 + s)(h_j + h_max) + beyond_a
// >= (1 + s)(h_i + h_j), so the pair (i, image of j) is not within reach; a corner image needs both of
// its axes within reach. The band is widened by a relative 1e-12 so that the rounding of 2 L - x_j
// cannot drop a pair at the very edge of the reach. Each particle gets one image per nonempty subset of
// its near axes (x, y and the corner xy for a quarter domain), written after the n particles in index
// order (deterministic).
void NeighbourSearch::add_mirror_images(const NeighbourInput& in, const Box& box, double h_max,
                                        double margin) {
  const std::size_t n = particles_;
  const double grow = 1.0 + options_.skin;
  const std::array<bool, 3> mirror = box.mirror;
  const std::array<double, 3> plane = box.lower;
  double beyond_x = 0.0, beyond_y = 0.0, beyond_z = 0.0;
#pragma omp parallel for schedule(static) reduction(max : beyond_x, beyond_y, beyond_z)
  for (std::size_t i = 0; i < n; ++i) {
    if (mirror[0]) beyond_x = std::max(beyond_x, plane[0] - xs_[i]);
    if (mirror[1]) beyond_y = std::max(beyond_y, plane[1] - ys_[i]);
    if (mirror[2]) beyond_z = std::max(beyond_z, plane[2] - zs_[i]);
  }
  // Kept lists (update()) widen both bands by a margin, so that a particle creeping across a plane, or
  // towards it, is not at once beyond what find_moved allows: the crossing allowed grows by the margin, and
  // particles up to a margin beyond the band find_moved requires get images too. The lists are unchanged
  // (they hold the pairs within reach), only more images sit in the tree.
  if (mirror[0]) beyond_x += margin;
  if (mirror[1]) beyond_y += margin;
  if (mirror[2]) beyond_z += margin;
  beyond_ = {beyond_x, beyond_y, beyond_z};
  near_planes_.resize(n);
  image_start_.resize(n + 1);
  image_start_[0] = 0;
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const double reach = grow * (in.smoothing_length[i] + h_max) * (1.0 + 1e-12);
    unsigned near = 0;
    if (mirror[0] && xs_[i] - plane[0] < reach + beyond_x + margin) near |= 1u;
    if (mirror[1] && ys_[i] - plane[1] < reach + beyond_y + margin) near |= 2u;
    if (mirror[2] && zs_[i] - plane[2] < reach + beyond_z + margin) near |= 4u;
    near_planes_[i] = static_cast<std::uint8_t>(near);
    image_start_[i + 1] = (1u << std::popcount(near)) - 1;  // nonempty subsets of `near`
  }
  for (std::size_t i = 0; i < n; ++i) image_start_[i + 1] += image_start_[i];
  const std::uint64_t entries = std::uint64_t{n} + image_start_[n];
  if (entries >= std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("neighbour search: " + std::to_string(entries) +
                                " particles and mirror images, more than 2^32-2");
  }
  const std::size_t slack = image_start_[n] / 4;
  resize_buffer(xs_, entries, slack);
  resize_buffer(ys_, entries, slack);
  resize_buffer(zs_, entries, slack);
  resize_buffer(keyed_, entries, slack);
  const MirrorPlanes planes = mirror_planes(box);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned near = near_planes_[i];
    std::size_t at = n + image_start_[i];
    for (unsigned bits = 1; bits < 8; ++bits) {
      if ((bits & ~near) != 0) continue;
      const MirrorImage image{i, bits};
      xs_[at] = image.position(0, planes, xs_[i]);
      ys_[at] = image.position(1, planes, ys_[i]);
      zs_[at] = image.position(2, planes, zs_[i]);
      keyed_[at].second = neighbour_entry(static_cast<std::uint32_t>(i), bits);
      ++at;
    }
  }
}

void NeighbourSearch::split_at_median(std::uint32_t begin, std::uint32_t end) {
  std::array<double, 3> lower{xs_[begin], ys_[begin], zs_[begin]}, upper = lower;
  for (std::uint32_t k = begin; k < end; ++k) {
    lower = {std::min(lower[0], xs_[k]), std::min(lower[1], ys_[k]), std::min(lower[2], zs_[k])};
    upper = {std::max(upper[0], xs_[k]), std::max(upper[1], ys_[k]), std::max(upper[2], zs_[k])};
  }
  int axis = 0;
  for (int a = 1; a < 3; ++a) {
    if (upper[a] - lower[a] > upper[axis] - lower[axis]) axis = a;
  }
  const std::vector<double>& coordinate = axis == 0 ? xs_ : (axis == 1 ? ys_ : zs_);
  std::vector<std::uint32_t> order(end - begin);  // rare path: a temporary is fine
  for (std::uint32_t k = begin; k < end; ++k) order[k - begin] = k;
  // Ties broken by index so the split is deterministic.
  std::nth_element(order.begin(), order.begin() + std::ptrdiff_t(order.size() / 2), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) {
                     return coordinate[a] < coordinate[b] || (coordinate[a] == coordinate[b] && a < b);
                   });
  // Apply the permutation to every sorted array (keys are all equal in this range).
  const auto apply = [&](auto& values) {
    auto copy = std::vector<typename std::decay_t<decltype(values)>::value_type>(order.size());
    for (std::size_t m = 0; m < order.size(); ++m) copy[m] = values[order[m]];
    std::copy(copy.begin(), copy.end(), values.begin() + begin);
  };
  apply(keyed_);
  apply(xs_);
  apply(ys_);
  apply(zs_);
  apply(hs_);
  apply(original_);
}

void NeighbourSearch::make_octree() {
  const std::size_t n = keyed_.size();
  groups_.clear();
  nodes_.clear();
  group_queried_.clear();
  if (n == 0) return;
  const std::size_t leaf_size = options_.leaf_size;
  // Depth-first construction over the sorted keys: a node of level L holds keys sharing their top 3L bits.
  // Chains of single-child levels are collapsed (the node keeps its range and descends a level).
  struct Frame {
    std::uint32_t begin, end;
    int level;
  };
  const auto build = [&](auto&& self, Frame f) -> std::uint32_t {
    const auto index = std::uint32_t(nodes_.size());
    nodes_.push_back({});
    int level = f.level;
    const auto digit = [&](std::uint32_t k, int lvl) {
      return int(keyed_[k].first >> (3 * (morton_bits_per_axis - 1 - lvl)) & 7);
    };
    while (f.end - f.begin > leaf_size && level < morton_bits_per_axis &&
           digit(f.begin, level) == digit(f.end - 1, level)) {
      ++level;
    }
    Node node{};
    if (f.end - f.begin <= leaf_size) {
      const auto g = std::uint32_t(groups_.size());
      Group group{{xs_[f.begin], ys_[f.begin], zs_[f.begin]},
                  {xs_[f.begin], ys_[f.begin], zs_[f.begin]},
                  0.0,
                  f.begin,
                  f.end};
      bool queried = false;
      for (std::uint32_t k = f.begin; k < f.end; ++k) {
        group.lower = {std::min(group.lower[0], xs_[k]), std::min(group.lower[1], ys_[k]),
                       std::min(group.lower[2], zs_[k])};
        group.upper = {std::max(group.upper[0], xs_[k]), std::max(group.upper[1], ys_[k]),
                       std::max(group.upper[2], zs_[k])};
        group.h_max = std::max(group.h_max, hs_[k]);
        queried = queried || mirror_bits(original_[k]) == 0;
      }
      groups_.push_back(group);
      group_queried_.push_back(queried ? 1 : 0);
      node = {group.lower, group.upper, group.h_max, 0, std::int32_t(g)};
    } else {
      constexpr double inf = std::numeric_limits<double>::infinity();
      node = {{inf, inf, inf}, {-inf, -inf, -inf}, 0.0, 0, -1};
      const auto add_child = [&](std::uint32_t b, std::uint32_t e, int child_level) {
        const std::uint32_t child = self(self, Frame{b, e, child_level});
        const Node& c = nodes_[child];
        for (int a = 0; a < 3; ++a) {
          node.lower[a] = std::min(node.lower[a], c.lower[a]);
          node.upper[a] = std::max(node.upper[a], c.upper[a]);
        }
        node.h_max = std::max(node.h_max, c.h_max);
      };
      if (level >= morton_bits_per_axis) {
        // More than leaf_size particles share one finest Morton cell: the bounding cube is over 2^21
        // times the particle spacing (e.g. a few particles thrown very far). Split at the median of the
        // longest axis instead (k-d), so that such a cell still costs O(n log n), not O(n^2).
        split_at_median(f.begin, f.end);
        const std::uint32_t middle = f.begin + (f.end - f.begin) / 2;
        add_child(f.begin, middle, level);
        add_child(middle, f.end, level);
      } else {
        for (std::uint32_t b = f.begin; b < f.end;) {
          const int d = digit(b, level);
          // End of this child's run: first key with a larger digit at this level.
          const auto it =
              std::partition_point(keyed_.begin() + b, keyed_.begin() + f.end, [&](const auto& item) {
                return int(item.first >> (3 * (morton_bits_per_axis - 1 - level)) & 7) <= d;
              });
          const auto e = std::uint32_t(it - keyed_.begin());
          add_child(b, e, level + 1);
          b = e;
        }
      }
    }
    node.skip = std::uint32_t(nodes_.size());
    nodes_[index] = node;
    return index;
  };
  build(build, Frame{0, std::uint32_t(n), 0});
}

template <bool Periodic>
void NeighbourSearch::candidates_octree(std::size_t g, const Box& box, std::vector<std::uint32_t>& out,
                                        double grow) const {
  const Group& group = groups_[g];
  const std::array<double, 3> edge{box.edge(0), box.edge(1), box.edge(2)};
  const std::size_t count = nodes_.size();
  for (std::size_t i = 0; i < count;) {
    const Node& node = nodes_[i];
    double d2 = 0;
    for (int a = 0; a < 3; ++a) {
      const double gap = interval_gap<Periodic>(group.lower[a], group.upper[a], node.lower[a], node.upper[a],
                                                box.periodic[a], edge[a]);
      d2 += gap * gap;
    }
    const double reach = grow * (group.h_max + node.h_max);
    if (d2 < reach * reach) {
      if (node.group >= 0) out.push_back(std::uint32_t(node.group));
      ++i;
    } else {
      i = node.skip;
    }
  }
}

// Three steps: index the sorted particles, find the candidate groups of every group, then write each real
// particle's list from its group's candidates.
template <bool Periodic>
void NeighbourSearch::collect_pairs(const Box& box, NeighbourLists& lists, double grow) {
  index_sorted_particles();
  find_candidate_groups<Periodic>(box, grow);
  const std::array<double, 3> edge{box.edge(0), box.edge(1), box.edge(2)};
  constexpr double inf = std::numeric_limits<double>::infinity();
  const GatherQuery query{edge,
                          {box.periodic[0] ? 0.5 * edge[0] : inf, box.periodic[1] ? 0.5 * edge[1] : inf,
                           box.periodic[2] ? 0.5 * edge[2] : inf},
                          box.periodic,
                          grow};
  write_lists<Periodic>(query, lists);
}

// rank_ (original index -> sorted index), group_of_ (sorted index -> group), one scratch per thread.
void NeighbourSearch::index_sorted_particles() {
  const std::size_t n = particles_;        // lists for the real particles only
  const std::size_t entries = xs_.size();  // particles and mirror images in the tree
  rank_.resize(n);
  resize_buffer(group_of_, entries, (entries - n) / 4);
#pragma omp parallel
  {
#pragma omp for schedule(static) nowait
    for (std::size_t k = 0; k < entries; ++k) {
      if (mirror_bits(original_[k]) == 0) rank_[original_[k]] = std::uint32_t(k);
    }
#pragma omp for schedule(static)
    for (std::size_t g = 0; g < groups_.size(); ++g) {
      for (std::uint32_t k = groups_[g].begin; k < groups_[g].end; ++k) group_of_[k] = std::uint32_t(g);
    }
  }
  if (scratch_.size() < std::size_t(omp_get_max_threads()))
    scratch_.resize(std::size_t(omp_get_max_threads()));
}

// Candidate groups of every group (CSR in candidate_offsets_, candidates_), counted then stored (finding
// them twice is cheap next to the pairs). Groups of images alone get none.
template <bool Periodic>
void NeighbourSearch::find_candidate_groups(const Box& box, double grow) {
  const std::size_t group_count = groups_.size();
  const auto find_candidates = [&](std::size_t g, std::vector<std::uint32_t>& out) {
    out.clear();
    if (group_queried_[g] != 0)
      candidates_octree<Periodic>(g, box, out, grow);  // images alone are never queried
  };
  candidate_offsets_.resize(group_count + 1);
  candidate_offsets_[0] = 0;
#pragma omp parallel
  {
    ThreadScratch& t = scratch_[std::size_t(omp_get_thread_num())];
#pragma omp for schedule(dynamic, 64)
    for (std::size_t g = 0; g < group_count; ++g) {
      find_candidates(g, t.candidates);
      candidate_offsets_[g + 1] = t.candidates.size();
    }
#pragma omp single
    {
      for (std::size_t g = 0; g < group_count; ++g) candidate_offsets_[g + 1] += candidate_offsets_[g];
      candidates_.resize(candidate_offsets_[group_count]);
    }
#pragma omp for schedule(dynamic, 64)
    for (std::size_t g = 0; g < group_count; ++g) {
      find_candidates(g, t.candidates);
      std::copy(t.candidates.begin(), t.candidates.end(),
                candidates_.begin() + std::ptrdiff_t(candidate_offsets_[g]));
    }
  }
}

// Neighbours of sorted particle k written to out[0..]; returns their number, or `room` + 1 when they
// might not fit in `room` entries (the test writes every candidate before deciding whether to keep it).
// Only the identical entry is dropped: a particle near a mirror plane keeps its own image.
template <bool Periodic>
std::size_t NeighbourSearch::gather_neighbours(std::uint32_t k, std::uint32_t* out, std::size_t room,
                                               const GatherQuery& query) const {
  const std::array<double, 3>& edge = query.edge;
  const std::array<double, 3>& half = query.half;
  const double grow = query.grow;
  const double* xs = xs_.data();
  const double* ys = ys_.data();
  const double* zs = zs_.data();
  const double* hs = hs_.data();
  const std::uint32_t g = group_of_[k];
  const double xi = xs[k], yi = ys[k], zi = zs[k], hi = hs[k];
  std::size_t used = 0;
  for (std::uint64_t c = candidate_offsets_[g]; c < candidate_offsets_[g + 1]; ++c) {
    const Group& o = groups_[candidates_[c]];
    // Point-to-box distance: skip the whole candidate when even its largest h cannot reach i.
    const double gx = interval_gap<Periodic>(xi, xi, o.lower[0], o.upper[0], query.periodic[0], edge[0]);
    const double gy = interval_gap<Periodic>(yi, yi, o.lower[1], o.upper[1], query.periodic[1], edge[1]);
    const double gz = interval_gap<Periodic>(zi, zi, o.lower[2], o.upper[2], query.periodic[2], edge[2]);
    const double box_reach = grow * (hi + o.h_max);
    if (gx * gx + gy * gy + gz * gz >= box_reach * box_reach) continue;
    if (used + (o.end - o.begin) > room) return room + 1;
    for (std::uint32_t block = o.begin; block < o.end; block += block_size) {
      const std::uint32_t length = std::min(o.end - block, block_size);
      const double* __restrict bx = xs + block;
      const double* __restrict by = ys + block;
      const double* __restrict bz = zs + block;
      const double* __restrict bh = hs + block;
      // Two steps: the distance tests (vectorised, no branches), then a branch-free compaction (the
      // test is unpredictable: about 1 in 3 candidates is a neighbour). margin > 0 exactly when
      // r^2 < reach^2 (IEEE subtraction of unequal finite numbers is nonzero).
      std::array<double, block_size> margin;
      for (std::uint32_t m = 0; m < length; ++m) {
        double dx = xi - bx[m], dy = yi - by[m], dz = zi - bz[m];
        if constexpr (Periodic) {  // minimum image, branch-free (half = infinity on open axes)
          dx = dx > half[0] ? dx - edge[0] : (dx < -half[0] ? dx + edge[0] : dx);
          dy = dy > half[1] ? dy - edge[1] : (dy < -half[1] ? dy + edge[1] : dy);
          dz = dz > half[2] ? dz - edge[2] : (dz < -half[2] ? dz + edge[2] : dz);
        }
        const double reach = grow * (hi + bh[m]);
        margin[m] = reach * reach - (dx * dx + dy * dy + dz * dz);
      }
      for (std::uint32_t m = 0; m < length; ++m) {
        out[used] = original_[block + m];
        used += std::size_t(margin[m] > 0) & std::size_t(block + m != k);
      }
    }
  }
  return used;
}

// The same into a growable vector from position `at`.
template <bool Periodic>
std::size_t NeighbourSearch::gather_neighbours_into(std::uint32_t k, std::vector<std::uint32_t>& v,
                                                    std::size_t at, const GatherQuery& query) const {
  for (;;) {
    const std::size_t room = v.size() - at;
    const std::size_t count = gather_neighbours<Periodic>(k, v.data() + at, room, query);
    if (count <= room) return count;
    v.resize(std::max(v.size() + v.size() / 2, at + 2 * room) + 1024);  // geometric growth
  }
}

// Lists are written in the caller's particle order straight into lists.neighbours: thread t owns a
// contiguous range of particles and a region of the array sized from a sample (every 16th particle's
// count, plus 3 % and a margin); one move closes the gaps between the regions afterwards. A thread
// that fills its region continues in its own overflow vector (rare: the merge then copies once).
// Three barriers per build in all, so that shared cores (where each barrier may cost a scheduler time
// slice) do not slow the build; about 3 % slack in the lists is the only extra memory.
template <bool Periodic>
void NeighbourSearch::write_lists(const GatherQuery& query, NeighbourLists& lists) {
  const std::size_t n = particles_;
  constexpr std::size_t sample_stride = 16;
  lists.offsets.resize(n + 1);
  lists.offsets[0] = 0;
  bool overflowed = false;
#pragma omp parallel
  {
    const auto threads = std::size_t(omp_get_num_threads());
    const auto id = std::size_t(omp_get_thread_num());
    ThreadScratch& t = scratch_[id];
    const std::size_t first = n * id / threads, last = n * (id + 1) / threads;
    std::size_t sampled = 0, samples = 0;
    for (std::size_t i = first; i < last; i += sample_stride, ++samples) {
      sampled += gather_neighbours_into<Periodic>(rank_[i], t.found, 0, query);
    }
    t.region_size =
        samples ? std::size_t(1.03 * double(sampled) * double(last - first) / double(samples)) : 0;
    if (last > first) t.region_size += 4096;  // margin for small ranges and sampling noise
#pragma omp barrier
#pragma omp single
    lay_out_regions(threads, lists);
    // implicit barrier: regions are laid out
    std::uint32_t* region = lists.neighbours.data() + t.region_start;
    std::size_t used = 0;
    t.overflow_from = last;
    t.used = 0;  // entries in the overflow vector
    for (std::size_t i = first; i < last; ++i) {
      const std::uint32_t k = rank_[i];
      std::size_t count = t.overflow_from == last
                              ? gather_neighbours<Periodic>(k, region + used, t.region_size - used, query)
                              : t.region_size + 1;
      if (count <= t.region_size - used) {
        used += count;
      } else {
        if (t.overflow_from == last) t.overflow_from = i;
        count = gather_neighbours_into<Periodic>(k, t.found, t.used, query);
        t.used += count;
      }
      lists.offsets[i + 1] = count;  // the count for now
    }
    t.region_used = used;
#pragma omp atomic update
    overflowed |= t.overflow_from != last;
#pragma omp barrier
#pragma omp single
    join_regions(threads, overflowed, lists);
    // implicit barrier; offsets: prefix sums over each thread's range from its final start
    std::uint64_t offset = t.final_start;
    for (std::size_t i = first; i < last; ++i) {
      offset += lists.offsets[i + 1];
      lists.offsets[i + 1] = offset;
    }
  }
}

// Each thread's region of lists.neighbours, one after the other, from the sizes the threads estimated.
void NeighbourSearch::lay_out_regions(std::size_t threads, NeighbourLists& lists) {
  std::size_t start = 0;
  for (std::size_t u = 0; u < threads; ++u) {
    scratch_[u].region_start = start;
    start += scratch_[u].region_size;
  }
  if (lists.neighbours.capacity() < start) {
    // The last build's entries are not read again: free them before allocating (no copy of them, one array
    // at a time), and leave room for the estimate's variation between builds. Reserving exactly the
    // estimate let about every other build of the Sedov bench allocate afresh, copying the old lists and
    // faulting in new pages (bench/RESULTS.md, "The lists' array allocated once").
    std::vector<std::uint32_t>().swap(lists.neighbours);
    lists.neighbours.reserve(start + start / 64);  // reserve, not resize: no doubling of the capacity
  }
  if (lists.neighbours.size() < start) lists.neighbours.resize(start);
}

// The threads' lists made contiguous in thread order (each thread's final_start set): the regions moved
// together, or, when a thread overflowed, regions and overflow vectors copied into a new array.
void NeighbourSearch::join_regions(std::size_t threads, bool overflowed, NeighbourLists& lists) {
  std::size_t base = 0;
  for (std::size_t u = 0; u < threads; ++u) {
    scratch_[u].final_start = base;
    base += scratch_[u].region_used + scratch_[u].used;
  }
  if (!overflowed) {
    // Close the gaps: every region moves down (final_start <= region_start when nothing overflowed),
    // in ascending order so that no data is overwritten before it is moved.
    for (std::size_t u = 1; u < threads; ++u) {
      const ThreadScratch& r = scratch_[u];
      if (r.region_used == 0) continue;  // (the array may be empty: no null pointer to memmove)
      std::memmove(lists.neighbours.data() + r.final_start, lists.neighbours.data() + r.region_start,
                   r.region_used * sizeof(std::uint32_t));
    }
  } else {
    std::vector<std::uint32_t> merged(base);
    for (std::size_t u = 0; u < threads; ++u) {
      const ThreadScratch& r = scratch_[u];
      auto out =
          std::copy_n(lists.neighbours.data() + r.region_start, r.region_used, merged.data() + r.final_start);
      std::copy_n(r.found.data(), r.used, out);
    }
    lists.neighbours.swap(merged);
  }
  lists.neighbours.resize(base);  // shrinking keeps the capacity for the next build
}

void NeighbourSearch::build(const NeighbourInput& input, const Box& box, NeighbourLists& lists) {
  built_ = false;
  sort_particles(input, box, false);
  make_octree();
  kept_ = false;
  const double grow = 1.0 + options_.skin;
  if (box.any_periodic()) {
    collect_pairs<true>(box, lists, grow);
  } else {
    collect_pairs<false>(box, lists, grow);
  }
  lists.ends.clear();
  box_ = box;
  built_ = true;
}

// Each list sorted by entry, in a slot with room to grow (slot_room; moved particles add themselves to the
// lists of their new neighbours). The lists are collected packed into the lists' own array and then spread
// into their slots in place, last list first (a slot starts at or after its packed list, and every list
// before it is still where it was collected): no second copy of the lists is held.
void NeighbourSearch::restructure(const NeighbourInput& input, const Box& box, NeighbourLists& lists) {
  built_ = false;
  kept_ = false;
  sort_particles(input, box, true);
  make_octree();
  const double grow = 1.0 + options_.skin;
  lists.ends.clear();
  if (box.any_periodic()) {
    collect_pairs<true>(box, lists, grow);
  } else {
    collect_pairs<false>(box, lists, grow);
  }
  box_ = box;
  built_ = true;
  ++restructures_;
  const std::size_t n = particles_;
  searches_ += n;
  lists.ends.resize(n);
  slot_end_.resize(n);
  std::uint64_t slots = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t count = lists.offsets[i + 1] - lists.offsets[i];
    slots += count + slot_room(count);
    slot_end_[i] = slots;
  }
  // Room for the slots that move before the next restructure: a sixteenth more. A capacity much beyond that,
  // left by an earlier layout with longer lists or by moved slots, is given back rather than held for the
  // rest of the run (the packed lists are copied once, at a restructure).
  const std::uint64_t wanted = slots + slots / 16;
  if (lists.neighbours.capacity() < slots || lists.neighbours.capacity() > wanted + wanted / 8) {
    std::vector<std::uint32_t> resized;
    resized.reserve(wanted);
    resized.assign(lists.neighbours.begin(), lists.neighbours.begin() + std::ptrdiff_t(lists.offsets[n]));
    lists.neighbours.swap(resized);
  }
  lists.neighbours.resize(slots);
  std::uint32_t* entries = lists.neighbours.data();
  for (std::size_t i = n; i-- > 0;) {
    const std::uint64_t packed = lists.offsets[i];
    const std::uint64_t count = lists.offsets[i + 1] - packed;
    const std::uint64_t slot = i == 0 ? 0 : slot_end_[i - 1];
    if (count > 0) std::memmove(entries + slot, entries + packed, count * sizeof(std::uint32_t));
    lists.offsets[i + 1] = slot_end_[i];
    lists.ends[i] = slot + count;
  }
  lists.offsets[0] = 0;
  unused_ = 0;
  const auto count = static_cast<std::int64_t>(n);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t ii = 0; ii < count; ++ii) {
    const auto i = static_cast<std::size_t>(ii);
    std::sort(entries + lists.offsets[i], entries + lists.ends[i]);
  }
  // The sorted index of every image entry (where move_anchors finds a moved particle's images).
  image_rank_.resize(box.any_mirror() ? image_start_[n] : 0);
  if (box.any_mirror()) {
#pragma omp parallel for schedule(static)
    for (std::size_t k = 0; k < original_.size(); ++k) {
      const std::uint32_t entry = original_[k];
      const unsigned bits = mirror_bits(entry);
      if (bits == 0) continue;
      const std::size_t i = neighbour_index(entry);
      // Images are numbered in increasing order of their bits among the subsets of near_planes_[i].
      unsigned m = 0;
      for (unsigned b = 1; b < bits; ++b) m += (b & ~unsigned(near_planes_[i])) == 0 ? 1u : 0u;
      image_rank_[image_start_[i] + m] = std::uint32_t(k);
    }
  }
  // The sort keys, the sorted index -> group map and the candidate groups serve only the collection of the
  // lists; the calls until the next restructure search the tree from the anchors and read none of them.
  // Freed here, they are no longer held through the substeps (about 25 bytes per particle with images); the
  // next restructure, at most every sort interval, allocates them again.
  release_build_buffers();
  kept_ = true;
}

// Marks the particles whose motion since their anchor exceeds the skin and records their new anchors.
// False when one of them needs a restructure: grown beyond build_h_max_ ((1 + s) times the build's largest h;
// the image reach and the periodic edge test assumed it), or, with mirror planes, come near a plane it has no
// image across, or further across a plane than any particle of the build (docs in add_mirror_images).
bool NeighbourSearch::find_moved(const NeighbourInput& input, const Box& box,
                                 std::span<const std::uint32_t> candidates, bool every_particle) {
  const std::size_t n = particles_;
  const double skin = options_.skin;
  if (moved_.size() != n) moved_.assign(n, 0);
  // moved_ is zero outside the last movers (a check of some particles reads and writes only theirs).
  for (const std::uint32_t i : moved_list_) {
    if (i < n) moved_[i] = 0;
  }
  if (scratch_.size() < std::size_t(omp_get_max_threads()))
    scratch_.resize(std::size_t(omp_get_max_threads()));
  const std::size_t count = every_particle ? n : candidates.size();
  // Each thread checks a contiguous range and lists its movers; the ranges joined in order give them in
  // index order without a second pass over every particle (this runs every substep, for a few movers).
  std::size_t threads = 1;
#pragma omp parallel
  {
#pragma omp single
    threads = std::size_t(omp_get_num_threads());
    const auto id = std::size_t(omp_get_thread_num());
    std::vector<std::uint32_t>& movers = scratch_[id].movers;
    movers.clear();
    const std::size_t first = count * id / std::size_t(omp_get_num_threads());
    const std::size_t last = count * (id + 1) / std::size_t(omp_get_num_threads());
    for (std::size_t c = first; c < last; ++c) {
      const std::size_t i = every_particle ? c : candidates[c];
      const std::size_t k = rank_[i];
      const double x = wrap_position(box, 0, input.x[i]);
      const double y = wrap_position(box, 1, input.y[i]);
      const double z = wrap_position(box, 2, input.z[i]);
      const auto d = displacement(box, x, y, z, xs_[k], ys_[k], zs_[k]);
      const double moved = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      const double grown = std::max(0.0, input.smoothing_length[i] - hs_[k]);
      // Written as !(<=) so that a NaN position or h is searched again (and reported by a restructure).
      const bool beyond = !(moved + grown <= skin * hs_[k]);
      if (beyond) {
        moved_[i] = 1;
        movers.push_back(std::uint32_t(i));
      }
    }
  }
  moved_list_.clear();
  for (std::size_t t = 0; t < threads; ++t)
    moved_list_.insert(moved_list_.end(), scratch_[t].movers.begin(), scratch_[t].movers.end());
  moved_anchor_.clear();
  const double grow = 1.0 + skin;
  bool fits = true;
  for (const std::uint32_t i : moved_list_) {
    const std::array<double, 4> anchor{wrap_position(box, 0, input.x[i]), wrap_position(box, 1, input.y[i]),
                                       wrap_position(box, 2, input.z[i]), input.smoothing_length[i]};
    moved_anchor_.push_back(anchor);
    if (!(anchor[3] <= build_h_max_) || !std::isfinite(anchor[0] + anchor[1] + anchor[2])) fits = false;
    if (box.any_mirror()) {
      const double reach = grow * (anchor[3] + build_h_max_) * (1.0 + 1e-12);
      for (int a = 0; a < 3; ++a) {
        if (!box.mirror[a]) continue;
        const double above = anchor[std::size_t(a)] - box.lower[a];
        const bool has_image = ((near_planes_[i] >> a) & 1u) != 0;
        if (above < -beyond_[std::size_t(a)] || (!has_image && above < reach + beyond_[std::size_t(a)])) {
          fits = false;
        }
      }
    }
  }
  return fits;
}

// The moved particles' new anchors into the sorted copies (their images reflected as sort_particles does),
// then the boxes of the tree around them.
void NeighbourSearch::move_anchors(const Box& box) {
  const MirrorPlanes planes = mirror_planes(box);
  dirty_groups_.clear();
  group_dirty_.resize(groups_.size());
  const auto mark_group = [this](std::size_t k) {
    // The group holding sorted index k: groups are contiguous ranges in increasing order.
    const auto after = std::upper_bound(groups_.begin(), groups_.end(), k,
                                        [](std::size_t rank, const Group& g) { return rank < g.begin; });
    const auto g = std::size_t(after - groups_.begin()) - 1;
    if (group_dirty_[g] != 0) return;
    group_dirty_[g] = 1;
    dirty_groups_.push_back(std::uint32_t(g));
  };
  for (std::size_t m = 0; m < moved_list_.size(); ++m) {
    const std::size_t i = moved_list_[m];
    const auto& anchor = moved_anchor_[m];
    const std::size_t k = rank_[i];
    xs_[k] = anchor[0];
    ys_[k] = anchor[1];
    zs_[k] = anchor[2];
    hs_[k] = anchor[3];
    mark_group(k);
    if (!box.any_mirror()) continue;
    for (std::uint32_t e = image_start_[i]; e < image_start_[i + 1]; ++e) {
      const std::size_t kk = image_rank_[e];
      const MirrorImage image = mirror_image(original_[kk]);
      xs_[kk] = image.position(0, planes, anchor[0]);
      ys_[kk] = image.position(1, planes, anchor[1]);
      zs_[kk] = image.position(2, planes, anchor[2]);
      hs_[kk] = anchor[3];
      mark_group(kk);
    }
  }
  refit_boxes();
}

// Tight boxes and largest h of the groups that hold a moved anchor (the others' are those of the last refit
// or build: the same min and max of unchanged anchors), then of every node, children before parents
// (depth-first order: a node's children follow it, so visiting the nodes backwards reaches every child
// first).
void NeighbourSearch::refit_boxes() {
  const auto dirty = static_cast<std::int64_t>(dirty_groups_.size());
#pragma omp parallel for schedule(static) if (dirty > 64)
  for (std::int64_t d = 0; d < dirty; ++d) {
    const std::size_t g = dirty_groups_[std::size_t(d)];
    group_dirty_[g] = 0;
    Group& group = groups_[g];
    group.lower = group.upper = {xs_[group.begin], ys_[group.begin], zs_[group.begin]};
    group.h_max = 0.0;
    for (std::uint32_t k = group.begin; k < group.end; ++k) {
      group.lower = {std::min(group.lower[0], xs_[k]), std::min(group.lower[1], ys_[k]),
                     std::min(group.lower[2], zs_[k])};
      group.upper = {std::max(group.upper[0], xs_[k]), std::max(group.upper[1], ys_[k]),
                     std::max(group.upper[2], zs_[k])};
      group.h_max = std::max(group.h_max, hs_[k]);
    }
  }
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (std::size_t k = nodes_.size(); k-- > 0;) {
    Node& node = nodes_[k];
    if (node.group >= 0) {
      const Group& group = groups_[std::size_t(node.group)];
      node.lower = group.lower;
      node.upper = group.upper;
      node.h_max = group.h_max;
      continue;
    }
    node.lower = {inf, inf, inf};
    node.upper = {-inf, -inf, -inf};
    node.h_max = 0.0;
    for (std::size_t c = k + 1; c < node.skip; c = nodes_[c].skip) {
      for (int a = 0; a < 3; ++a) {
        node.lower[a] = std::min(node.lower[a], nodes_[c].lower[a]);
        node.upper[a] = std::max(node.upper[a], nodes_[c].upper[a]);
      }
      node.h_max = std::max(node.h_max, nodes_[c].h_max);
    }
  }
}

// The list of particle i at the anchors: every entry whose anchor is within (1 + s)(H_i + H_j) of i's (its
// own images included, itself not), by a walk of the tree from its root, sorted.
template <bool Periodic>
void NeighbourSearch::search_anchor(std::uint32_t i, const Box& box, std::vector<std::uint32_t>& out) const {
  out.clear();
  const std::array<double, 3> edge{box.edge(0), box.edge(1), box.edge(2)};
  std::array<double, 3> half{};
  for (int a = 0; a < 3; ++a) {
    half[std::size_t(a)] =
        box.periodic[a] ? 0.5 * edge[std::size_t(a)] : std::numeric_limits<double>::infinity();
  }
  const double grow = 1.0 + options_.skin;
  const std::uint32_t self = rank_[i];
  const double xi = xs_[self], yi = ys_[self], zi = zs_[self], hi = hs_[self];
  for (std::size_t at = 0; at < nodes_.size();) {
    const Node& node = nodes_[at];
    const double gx = interval_gap<Periodic>(xi, xi, node.lower[0], node.upper[0], box.periodic[0], edge[0]);
    const double gy = interval_gap<Periodic>(yi, yi, node.lower[1], node.upper[1], box.periodic[1], edge[1]);
    const double gz = interval_gap<Periodic>(zi, zi, node.lower[2], node.upper[2], box.periodic[2], edge[2]);
    const double box_reach = grow * (hi + node.h_max);
    if (gx * gx + gy * gy + gz * gz >= box_reach * box_reach) {
      at = node.skip;
      continue;
    }
    if (node.group >= 0) {
      const Group& g = groups_[std::size_t(node.group)];
      for (std::uint32_t k = g.begin; k < g.end; ++k) {
        double dx = xi - xs_[k], dy = yi - ys_[k], dz = zi - zs_[k];
        if constexpr (Periodic) {
          dx = dx > half[0] ? dx - edge[0] : (dx < -half[0] ? dx + edge[0] : dx);
          dy = dy > half[1] ? dy - edge[1] : (dy < -half[1] ? dy + edge[1] : dy);
          dz = dz > half[2] ? dz - edge[2] : (dz < -half[2] ? dz + edge[2] : dz);
        }
        const double reach = grow * (hi + hs_[k]);
        if (reach * reach - (dx * dx + dy * dy + dz * dz) > 0 && k != self &&
            (removed_.empty() || removed_[k] == 0)) {
          out.push_back(original_[k]);
        }
      }
    }
    ++at;
  }
  std::sort(out.begin(), out.end());
}

// Moves list i to a new slot at the end of the array with room for `room` entries.
void NeighbourSearch::move_slot(NeighbourLists& lists, std::size_t i, std::size_t room) {
  const std::uint64_t count = lists.count(i);
  const std::uint64_t capacity = std::max<std::uint64_t>(room, count) + slot_room(count);
  const std::uint64_t start = lists.neighbours.size();
  // Grown by an eighth, not doubled: the array holds every list, and a doubling would be held until the next
  // restructure gives it back.
  const std::uint64_t size = start + capacity;
  if (lists.neighbours.capacity() < size) lists.neighbours.reserve(size + size / 8);
  lists.neighbours.resize(start + capacity);
  std::copy(lists.neighbours.begin() + std::ptrdiff_t(lists.offsets[i]),
            lists.neighbours.begin() + std::ptrdiff_t(lists.ends[i]),
            lists.neighbours.begin() + std::ptrdiff_t(start));
  unused_ += slot_end_[i] - lists.offsets[i];
  lists.offsets[i] = start;
  lists.ends[i] = start + count;
  slot_end_[i] = start + capacity;
}

// Adds `entry` to list j at its sorted place unless it is there.
void NeighbourSearch::insert_entry(NeighbourLists& lists, std::size_t j, std::uint32_t entry) {
  std::uint32_t* begin = lists.neighbours.data() + lists.offsets[j];
  std::uint32_t* end = lists.neighbours.data() + lists.ends[j];
  std::uint32_t* at = std::lower_bound(begin, end, entry);
  if (at != end && *at == entry) return;
  if (lists.ends[j] == slot_end_[j]) {
    const auto place = at - begin;
    move_slot(lists, j, lists.count(j) + 1);
    begin = lists.neighbours.data() + lists.offsets[j];
    end = lists.neighbours.data() + lists.ends[j];
    at = begin + place;
  }
  std::copy_backward(at, end, end + 1);
  *at = entry;
  ++lists.ends[j];
}

// The moved particles' new lists into their slots, and each of them into the lists of its new neighbours
// (the criterion is symmetric: image_A(j) in list(i) iff image_A(i) in list(j)), in index order. Entries of a
// moved particle's old anchor stay in the others' lists: a superset is a valid list.
void NeighbourSearch::write_moved_lists(NeighbourLists& lists) {
  for (std::size_t m = 0; m < moved_list_.size(); ++m) {
    const std::size_t i = moved_list_[m];
    const std::span<const std::uint32_t> fresh = fresh_[m];
    if (lists.offsets[i] + fresh.size() > slot_end_[i]) {
      lists.ends[i] = lists.offsets[i];  // nothing to carry over
      move_slot(lists, i, fresh.size());
    }
    std::copy(fresh.begin(), fresh.end(), lists.neighbours.begin() + std::ptrdiff_t(lists.offsets[i]));
    lists.ends[i] = lists.offsets[i] + fresh.size();
  }
  for (std::size_t m = 0; m < moved_list_.size(); ++m) {
    const auto i = moved_list_[m];
    for (const std::uint32_t entry : fresh_[m]) {
      const std::size_t j = neighbour_index(entry);
      if (moved_[j] != 0) continue;  // its new list has i already
      insert_entry(lists, j, neighbour_entry(i, mirror_bits(entry)));
    }
  }
}

bool NeighbourSearch::keeps_layout(const NeighbourInput& input, const Box& box,
                                   const NeighbourLists& lists) const {
  const std::size_t n = input.x.size();
  const bool same_layout = kept_ && built_ && !nodes_.empty() && n == particles_ && input.y.size() == n &&
                           input.z.size() == n && input.smoothing_length.size() == n &&
                           box.periodic == box_.periodic && box.mirror == box_.mirror &&
                           box.lower == box_.lower && box.upper == box_.upper &&
                           lists.particle_count() == n && lists.ends.size() == n;
  // Abandoned slots beyond the lists' own size: lay the lists out afresh.
  const bool wasteful = unused_ > lists.neighbours.size() / 2;
  return same_layout && !wasteful;
}

void NeighbourSearch::update(const NeighbourInput& input, const Box& box, NeighbourLists& lists,
                             bool restructure_now) {
  if (restructure_now || !keeps_layout(input, box, lists) || !find_moved(input, box, {}, true)) {
    restructure(input, box, lists);
    return;
  }
  search_moved(box, lists);
}

bool NeighbourSearch::update_moved(const NeighbourInput& input, const Box& box, NeighbourLists& lists,
                                   std::span<const std::uint32_t> candidates) {
  if (!keeps_layout(input, box, lists)) return false;
  if (!find_moved(input, box, candidates, false)) {
    for (const std::uint32_t i : moved_list_) moved_[i] = 0;
    moved_list_.clear();
    return false;
  }
  search_moved(box, lists);
  return true;
}

double NeighbourSearch::room(std::size_t i, double x, double y, double z, double h, const Box& box) const {
  const std::size_t k = rank_[i];
  const auto d = displacement(box, wrap_position(box, 0, x), wrap_position(box, 1, y),
                              wrap_position(box, 2, z), xs_[k], ys_[k], zs_[k]);
  return options_.skin * hs_[k] - std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) -
         std::max(0.0, h - hs_[k]);
}

void NeighbourSearch::search_moved(const Box& box, NeighbourLists& lists) {
  if (moved_list_.empty()) return;
  move_anchors(box);
  searches_ += moved_list_.size();
  // Their new lists: each thread searches a contiguous range of them into its own buffer, where
  // write_moved_lists reads them (in index order) through one span per moved particle.
  const std::size_t moved = moved_list_.size();
  fresh_start_.resize(moved);
  fresh_.resize(moved);
  const bool periodic = box.any_periodic();
#pragma omp parallel
  {
    const auto threads = std::size_t(omp_get_num_threads());
    const auto id = std::size_t(omp_get_thread_num());
    ThreadScratch& t = scratch_[id];
    const std::size_t first = moved * id / threads, last = moved * (id + 1) / threads;
    t.found.clear();
    for (std::size_t m = first; m < last; ++m) {
      if (periodic) {
        search_anchor<true>(moved_list_[m], box, t.candidates);
      } else {
        search_anchor<false>(moved_list_[m], box, t.candidates);
      }
      fresh_start_[m] = t.found.size();
      t.found.insert(t.found.end(), t.candidates.begin(), t.candidates.end());
    }
    for (std::size_t m = first; m < last; ++m) {  // the buffer no longer moves
      const std::size_t end = m + 1 < last ? fresh_start_[m + 1] : t.found.size();
      fresh_[m] = std::span<const std::uint32_t>(t.found.data() + fresh_start_[m], end - fresh_start_[m]);
    }
  }
  write_moved_lists(lists);
}

bool NeighbourSearch::remove_particles(std::span<const std::uint32_t> order, std::size_t kept,
                                       NeighbourLists& lists) {
  const std::size_t n = particles_;
  if (!kept_ || !built_ || kept > n || order.size() < n || lists.particle_count() != n ||
      lists.ends.size() != n) {
    return false;
  }
  for (std::size_t k = 0; k < kept; ++k) {
    if (order[k] >= n || (k > 0 && order[k] <= order[k - 1])) return false;
  }
  constexpr std::uint32_t gone = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> new_index(n, gone);  // once per ejection, not per substep
  for (std::size_t k = 0; k < kept; ++k) new_index[order[k]] = std::uint32_t(k);
  // The stayers' lists without the leavers, renumbered in place (order kept: the map is increasing).
  std::uint32_t* entries = lists.neighbours.data();
  const auto count = static_cast<std::int64_t>(kept);
#pragma omp parallel for schedule(dynamic, 256)
  for (std::int64_t kk = 0; kk < count; ++kk) {
    const std::size_t i = order[std::size_t(kk)];
    std::uint32_t* out = entries + lists.offsets[i];
    for (std::uint64_t e = lists.offsets[i]; e < lists.ends[i]; ++e) {
      const std::uint32_t j = new_index[neighbour_index(entries[e])];
      if (j != gone) *out++ = neighbour_entry(j, mirror_bits(entries[e]));
    }
    lists.ends[i] = std::uint64_t(out - entries);
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (new_index[i] == gone) unused_ += slot_end_[i] - lists.offsets[i];
  }
  // Per-particle state moved down to the new indices (order[k] >= k: a forward pass reads nothing it wrote).
  const bool mirrored = box_.any_mirror();
  std::uint32_t images = 0;
  for (std::size_t k = 0; k < kept; ++k) {
    const std::size_t i = order[k];
    lists.offsets[k] = lists.offsets[i];
    lists.ends[k] = lists.ends[i];
    slot_end_[k] = slot_end_[i];
    rank_[k] = rank_[i];
    if (mirrored) {
      near_planes_[k] = near_planes_[i];
      const std::uint32_t first = image_start_[i], last = image_start_[i + 1];
      image_start_[k] = images;
      for (std::uint32_t e = first; e < last; ++e) image_rank_[images++] = image_rank_[e];
    }
  }
  lists.offsets.resize(kept + 1);
  lists.offsets[kept] = lists.neighbours.size();
  lists.ends.resize(kept);
  slot_end_.resize(kept);
  rank_.resize(kept);
  if (mirrored) {
    near_planes_.resize(kept);
    image_start_.resize(kept + 1);
    image_start_[kept] = images;
    image_rank_.resize(images);
  }
  // The sorted entries (particles and images): renumbered, or marked as left.
  if (removed_.empty()) removed_.assign(original_.size(), 0);
  for (std::size_t k = 0; k < original_.size(); ++k) {
    if (removed_[k] != 0) continue;
    const std::uint32_t j = new_index[neighbour_index(original_[k])];
    if (j == gone) {
      removed_[k] = 1;
    } else {
      original_[k] = neighbour_entry(j, mirror_bits(original_[k]));
    }
  }
  particles_ = kept;
  return true;
}

bool NeighbourSearch::needs_rebuild(const NeighbourInput& input) const {
  const std::size_t n = particles_;
  if (!built_ || !removed_.empty() || input.x.size() != n || input.y.size() != n || input.z.size() != n ||
      input.smoothing_length.size() != n) {
    return true;
  }
  const double skin = options_.skin;
  const std::size_t entries = xs_.size();
  bool moved_too_far = false;
  // The real particles only: an image moves exactly as its source does (header).
#pragma omp parallel for schedule(static) reduction(|| : moved_too_far)
  for (std::size_t k = 0; k < entries; ++k) {
    if (mirror_bits(original_[k]) != 0) continue;
    const std::uint32_t i = original_[k];
    const auto d = displacement(box_, input.x[i], input.y[i], input.z[i], xs_[k], ys_[k], zs_[k]);
    const double moved = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    const double grown = std::max(0.0, input.smoothing_length[i] - hs_[k]);
    // Written as !(<=) so that a NaN position or h asks for a rebuild (which then reports it).
    if (!(moved + grown <= skin * hs_[k])) moved_too_far = true;
  }
  return moved_too_far;
}

}  // namespace craterkit::sph
