// The column grid of the crater measurement (crater_columns.hpp).
#include "crater_columns.hpp"

#include <string>
#include <utility>

#include "craterkit/common/input_error.hpp"

namespace craterkit::impact::crater_detail {

using namespace sph;
namespace {

// Indices of the particles that count for the density (not flagged ejected); each must have a finite
// smoothing length > 0, since the cell size and every kernel evaluation depend on it.
std::vector<std::uint32_t> non_ejected_particles(const Particles& p) {
  std::vector<std::uint32_t> kept;
  kept.reserve(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    if ((p.flags[i] & particle_ejected) != 0) continue;
    if (!(p.smoothing_length[i] > 0.0) || !std::isfinite(p.smoothing_length[i])) {
      throw InputError("particle id " + std::to_string(p.id[i]) + ": smoothing_length " +
                       std::to_string(p.smoothing_length[i]) + " must be a finite number > 0");
    }
    kept.push_back(static_cast<std::uint32_t>(i));
  }
  return kept;
}

// The 99.9th percentile of the smoothing lengths of `kept` (not empty): the cell size is set by it, so
// that a few expanded particles do not coarsen the grid for all.
double smoothing_length_percentile(const Particles& p, const std::vector<std::uint32_t>& kept) {
  std::vector<double> hs(kept.size());
  for (std::size_t k = 0; k < kept.size(); ++k) hs[k] = p.smoothing_length[kept[k]];
  const std::size_t q = std::min(kept.size() - 1, static_cast<std::size_t>(0.999 * double(kept.size())));
  std::nth_element(hs.begin(), hs.begin() + static_cast<std::ptrdiff_t>(q), hs.end());
  return hs[q];
}

// The points of the density field: the kept particles, each followed by its three mirror images
// (about x = centre x, y = centre y and both) on a quarter domain.
std::vector<ColumnGrid::Point> density_points(const Particles& p, const std::vector<std::uint32_t>& kept,
                                              bool quarter, const std::array<double, 2>& centre) {
  std::vector<ColumnGrid::Point> all;
  all.reserve(kept.size() * (quarter ? 4 : 1));
  for (const std::uint32_t i : kept) {
    all.push_back({p.x[i], p.y[i], p.z[i], p.smoothing_length[i], p.mass[i]});
    if (!quarter) continue;
    const double mx = 2.0 * centre[0] - p.x[i], my = 2.0 * centre[1] - p.y[i];
    all.push_back({mx, p.y[i], p.z[i], p.smoothing_length[i], p.mass[i]});
    all.push_back({p.x[i], my, p.z[i], p.smoothing_length[i], p.mass[i]});
    all.push_back({mx, my, p.z[i], p.smoothing_length[i], p.mass[i]});
  }
  return all;
}

}  // namespace

ColumnGrid::ColumnGrid(const Particles& p, bool quarter, const std::array<double, 2>& centre) {
  const std::vector<std::uint32_t> kept = non_ejected_particles(p);
  if (kept.empty()) return;
  h_cell_ = smoothing_length_percentile(p, kept);
  edge_ = 2.0 * h_cell_;
  const std::vector<Point> all = density_points(p, kept, quarter, centre);
  bin(all);
  count_ = all.size();
}

void ColumnGrid::bin(const std::vector<Point>& all) {
  // (cell key, index in `all`), sorted: the cells in key order, each holding its points in their order
  // in `all`.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keyed;
  keyed.reserve(all.size());
  for (std::size_t k = 0; k < all.size(); ++k) {
    if (all[k].h > h_cell_) {
      big_.push_back(all[k]);
      continue;
    }
    keyed.emplace_back(key(cell(all[k].x), cell(all[k].y)), static_cast<std::uint32_t>(k));
  }
  std::sort(keyed.begin(), keyed.end());
  points_.reserve(keyed.size());
  for (std::size_t k = 0; k < keyed.size(); ++k) {
    if (k == 0 || keyed[k].first != keyed[k - 1].first) {
      keys_.push_back(keyed[k].first);
      starts_.push_back(static_cast<std::uint32_t>(k));
    }
    points_.push_back(all[keyed[k].second]);
  }
  starts_.push_back(static_cast<std::uint32_t>(keyed.size()));
}

void ColumnGrid::gather(double x, double y, Column& column) const {
  column.entries.clear();
  column.groups.clear();
  column.heights.clear();
  column.reach = 0.0;
  double h_min = std::numeric_limits<double>::infinity();
  for_near(x, y, [&](const Point& pt) {
    const double dx = pt.x - x, dy = pt.y - y;
    const double r2 = dx * dx + dy * dy;
    if (r2 < 4.0 * pt.h * pt.h) {
      column.entries.push_back({pt.z, r2, pt.h, pt.m, 0});
      column.reach = std::max(column.reach, 2.0 * pt.h);
      h_min = std::min(h_min, pt.h);
    }
  });
  bool one_group = true;
  for (ColumnEntry& e : column.entries) {
    // h < 2 h_min is group 0 without a logarithm (all of them when the smoothing lengths are equal).
    e.group = e.h < 2.0 * h_min ? 0 : static_cast<int>(std::floor(std::log2(e.h / h_min)));
    one_group = one_group && e.group == 0;
  }
  std::sort(column.entries.begin(), column.entries.end(), [](const ColumnEntry& a, const ColumnEntry& b) {
    return a.group < b.group || (a.group == b.group && a.z < b.z);
  });
  for (std::size_t k = 0; k < column.entries.size(); ++k) {
    const ColumnEntry& e = column.entries[k];
    if (k == 0 || e.group != column.entries[k - 1].group) column.groups.push_back({k, k, 0.0});
    column.groups.back().end = k + 1;
    column.groups.back().reach = std::max(column.groups.back().reach, 2.0 * e.h);
    column.heights.push_back(e.z);
  }
  if (!one_group) std::sort(column.heights.begin(), column.heights.end());
}

}  // namespace craterkit::impact::crater_detail
