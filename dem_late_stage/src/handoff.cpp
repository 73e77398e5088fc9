#include "craterkit/dem_late_stage/handoff.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <unordered_map>

#include "craterkit/common/checks.hpp"
#include "craterkit/common/input_error.hpp"

namespace craterkit::dem_late_stage {

namespace {

// The SPH particles that flow on into the late stage, with their mirror images across x = 0 and y = 0 in a
// quarter-domain run, binned into cubic cells for the gather around each grain.
struct FlowingMaterial {
  std::vector<double> x, y, z, vx, vy, vz, mass, smoothing_length;
  double cell = 0.0;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;

  void add(const sph::Particles& p, std::size_t i, double sx, double sy) {
    x.push_back(sx * p.x[i]);
    y.push_back(sy * p.y[i]);
    z.push_back(p.z[i]);
    vx.push_back(sx * p.vx[i]);
    vy.push_back(sy * p.vy[i]);
    vz.push_back(p.vz[i]);
    mass.push_back(p.mass[i]);
    smoothing_length.push_back(p.smoothing_length[i]);
  }

  static std::uint64_t key(long ix, long iy, long iz) {
    constexpr long offset = 1L << 20;  // cells are at most 2^20 either side of the origin
    return (static_cast<std::uint64_t>(ix + offset) << 42) | (static_cast<std::uint64_t>(iy + offset) << 21) |
           static_cast<std::uint64_t>(iz + offset);
  }
  [[nodiscard]] long index(double coordinate) const {
    return static_cast<long>(std::floor(coordinate / cell));
  }

  void bin(double cell_size) {
    cell = cell_size;
    for (std::uint32_t j = 0; j < x.size(); ++j)
      cells[key(index(x[j]), index(y[j]), index(z[j]))].push_back(j);
  }

  template <class F>
  void for_each_near(double px, double py, double pz, F&& f) const {
    const long cx = index(px), cy = index(py), cz = index(pz);
    for (long ix = cx - 1; ix <= cx + 1; ++ix)
      for (long iy = cy - 1; iy <= cy + 1; ++iy)
        for (long iz = cz - 1; iz <= cz + 1; ++iz) {
          const auto found = cells.find(key(ix, iy, iz));
          if (found == cells.end()) continue;
          for (const std::uint32_t j : found->second) f(j);
        }
  }
};

void add_particle(MotionTotals& totals, const sph::Particles& p, std::size_t i) {
  totals.count += 1;
  totals.mass += p.mass[i];
  totals.momentum[0] += p.mass[i] * p.vx[i];
  totals.momentum[1] += p.mass[i] * p.vy[i];
  totals.momentum[2] += p.mass[i] * p.vz[i];
  totals.kinetic_energy += 0.5 * p.mass[i] * (p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
}

// omega = curl(v) / 2 from the weighted least-squares velocity gradient G = B A^-1 (A = sum w r r^T,
// B = sum w dv r^T); zero when A is singular (the neighbours do not span three dimensions).
std::array<double, 3> spin_of_flow(const std::array<double, 9>& a, const std::array<double, 9>& b) {
  const double det = a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6]) +
                     a[2] * (a[3] * a[7] - a[4] * a[6]);
  const double scale = (a[0] + a[4] + a[8]) / 3.0;
  if (!(scale > 0.0) || !(std::abs(det) > 1e-6 * scale * scale * scale)) return {0.0, 0.0, 0.0};
  std::array<double, 9> inverse{(a[4] * a[8] - a[5] * a[7]) / det, (a[2] * a[7] - a[1] * a[8]) / det,
                                (a[1] * a[5] - a[2] * a[4]) / det, (a[5] * a[6] - a[3] * a[8]) / det,
                                (a[0] * a[8] - a[2] * a[6]) / det, (a[2] * a[3] - a[0] * a[5]) / det,
                                (a[3] * a[7] - a[4] * a[6]) / det, (a[1] * a[6] - a[0] * a[7]) / det,
                                (a[0] * a[4] - a[1] * a[3]) / det};
  std::array<double, 9> g{};  // g[3 r + c] = dv_r / dx_c
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) g[3 * r + c] += b[3 * r + k] * inverse[3 * k + c];
  return {0.5 * (g[7] - g[5]), 0.5 * (g[2] - g[6]), 0.5 * (g[3] - g[1])};
}

}  // namespace

void check_handoff_spec(const HandoffSpec& spec) {
  const auto& box = spec.bed_box;
  if (!(box.x_low == 0.0 && box.y_low == 0.0))
    throw InputError("handoff.bed_box: must start at x = 0, y = 0 (the mirror planes)");
  require_positive(box.x_high, "handoff.bed_box.x_high");
  require_positive(box.y_high, "handoff.bed_box.y_high");
  if (!(box.z_high > box.z_low)) throw InputError("handoff.bed_box: z_high must lie above z_low");
  require_positive(spec.frozen_thickness, "handoff.frozen_thickness");
  require_positive(spec.critical_density, "handoff.critical_density");
  require_positive(spec.ejecta_speed, "handoff.ejecta_speed");
  require_positive(spec.flying_grain_density, "handoff.flying_grain_density");
  require_non_negative(spec.sph_domain_radius, "handoff.sph_domain_radius");
}

MotionTotals grain_totals(const dem::Grains& grains, const std::vector<int>& roles, GrainRole role) {
  MotionTotals totals;
  for (std::size_t g = 0; g < grains.size(); ++g) {
    if (roles[g] != static_cast<int>(role)) continue;
    const double m = grains.mass(g);
    const double inertia = 0.1 * m * grains.diameter[g] * grains.diameter[g];
    totals.count += 1;
    totals.mass += m;
    totals.momentum[0] += m * grains.vx[g];
    totals.momentum[1] += m * grains.vy[g];
    totals.momentum[2] += m * grains.vz[g];
    totals.kinetic_energy +=
        0.5 * m * (grains.vx[g] * grains.vx[g] + grains.vy[g] * grains.vy[g] + grains.vz[g] * grains.vz[g]) +
        0.5 * inertia *
            (grains.omega_x[g] * grains.omega_x[g] + grains.omega_y[g] * grains.omega_y[g] +
             grains.omega_z[g] * grains.omega_z[g]);
  }
  return totals;
}

Handoff hand_off(const sph::Particles& sph, const dem::Grains& bed, const HandoffSpec& spec) {
  check_handoff_spec(spec);
  const auto& box = spec.bed_box;
  Handoff out;
  auto& balance = out.balance;

  // 1. The split of the SPH particles.
  FlowingMaterial flowing;
  double max_diameter = 0.0;
  for (std::size_t g = 0; g < bed.size(); ++g) max_diameter = std::max(max_diameter, bed.diameter[g]);
  double max_support = max_diameter;
  std::vector<std::size_t> flying;
  for (std::size_t i = 0; i < sph.size(); ++i) {
    if (sph.flags[i] & sph::particle_ejected) {
      add_particle(balance.sph_ejected, sph, i);
      continue;
    }
    const double speed = std::sqrt(sph.vx[i] * sph.vx[i] + sph.vy[i] * sph.vy[i] + sph.vz[i] * sph.vz[i]);
    if (speed > spec.ejecta_speed && sph.vz[i] > 0.0 && sph.z[i] > 0.0 &&
        !(sph.flags[i] & sph::particle_fixed)) {
      add_particle(balance.sph_flying, sph, i);
      flying.push_back(i);
      continue;
    }
    const bool in_bed =
        sph.x[i] <= box.x_high && sph.y[i] <= box.y_high && sph.z[i] >= box.z_low && sph.z[i] <= box.z_high;
    add_particle(in_bed ? balance.sph_in_bed : balance.sph_outside_bed, sph, i);
    max_support = std::max(max_support, 2.0 * sph.smoothing_length[i]);
    const int images = spec.quarter_symmetric ? 4 : 1;
    for (int image = 0; image < images; ++image) {
      const double sx = (image & 1) ? -1.0 : 1.0, sy = (image & 2) ? -1.0 : 1.0;
      // An image matters only within a kernel support of its plane.
      const double reach = std::max(2.0 * sph.smoothing_length[i], max_diameter);
      if (sx < 0 && sph.x[i] > reach) continue;
      if (sy < 0 && sph.y[i] > reach) continue;
      flowing.add(sph, i, sx, sy);
    }
  }
  flowing.bin(max_support);
  const double domain_limit = spec.sph_domain_radius > 0.0 ? spec.sph_domain_radius - max_support : 0.0;

  // 2-4. Carve, set moving, freeze.
  struct Neighbour {
    std::uint32_t index;
    double weight;
  };
  std::vector<Neighbour> near;  // the neighbours of one grain that weigh in its motion, kept for the fit
  sph::with_kernel(spec.kernel, [&](auto kernel) {
    for (std::size_t g = 0; g < bed.size(); ++g) {
      const double gx = bed.x[g], gy = bed.y[g], gz = bed.z[g], d = bed.diameter[g];
      double density = 0.0, weight = 0.0;
      std::array<double, 3> momentum{0.0, 0.0, 0.0}, centroid{0.0, 0.0, 0.0};
      near.clear();
      flowing.for_each_near(gx, gy, gz, [&](std::uint32_t j) {
        const double dx = flowing.x[j] - gx, dy = flowing.y[j] - gy, dz = flowing.z[j] - gz;
        const double r = std::sqrt(dx * dx + dy * dy + dz * dz);
        density += flowing.mass[j] * kernel.value(r, flowing.smoothing_length[j]);
        const double w = flowing.mass[j] * kernel.value(r, std::max(flowing.smoothing_length[j], 0.5 * d));
        if (w > 0.0) near.push_back({j, w});
        weight += w;
        momentum[0] += w * flowing.vx[j];
        momentum[1] += w * flowing.vy[j];
        momentum[2] += w * flowing.vz[j];
        centroid[0] += w * dx;
        centroid[1] += w * dy;
        centroid[2] += w * dz;
      });
      const double radius = std::sqrt(gx * gx + gy * gy + gz * gz);
      const bool undisturbed_ground = domain_limit > 0.0 && radius > domain_limit && gz < 0.0;
      const bool frozen = gx > box.x_high - spec.frozen_thickness ||
                          gy > box.y_high - spec.frozen_thickness || gz < box.z_low + spec.frozen_thickness;
      if (!(density >= spec.critical_density) && !undisturbed_ground && !frozen) {
        ++balance.grains_carved;
        continue;
      }
      out.grains.add(gx, gy, gz, d, bed.density[g]);
      out.roles.push_back(static_cast<int>(frozen ? GrainRole::frozen : GrainRole::moving));
      if (frozen) continue;
      if (!(weight > 0.0)) {
        ++balance.grains_without_neighbours;
        continue;
      }
      const std::array<double, 3> v{momentum[0] / weight, momentum[1] / weight, momentum[2] / weight};
      // The fit about the weighted centroid of the neighbours, where the weighted mean velocity v sits: exact
      // for a linear field.
      for (auto& c : centroid) c /= weight;
      std::array<double, 9> a{}, b{};
      for (const auto& [j, w] : near) {
        const std::array<double, 3> r{flowing.x[j] - gx - centroid[0], flowing.y[j] - gy - centroid[1],
                                      flowing.z[j] - gz - centroid[2]};
        const std::array<double, 3> dv{flowing.vx[j] - v[0], flowing.vy[j] - v[1], flowing.vz[j] - v[2]};
        for (int row = 0; row < 3; ++row)
          for (int col = 0; col < 3; ++col) {
            a[3 * row + col] += w * r[row] * r[col];
            b[3 * row + col] += w * dv[row] * r[col];
          }
      }
      const auto omega = spin_of_flow(a, b);
      const std::size_t k = out.grains.size() - 1;
      out.grains.vx[k] = v[0];
      out.grains.vy[k] = v[1];
      out.grains.vz[k] = v[2];
      out.grains.omega_x[k] = omega[0];
      out.grains.omega_y[k] = omega[1];
      out.grains.omega_z[k] = omega[2];
      balance.max_moving_speed =
          std::max(balance.max_moving_speed, std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]));
    }
  });

  // Fast ejecta: one grain each, of the SPH particle's mass, position and velocity.
  for (const std::size_t i : flying) {
    const double d = std::cbrt(6.0 * sph.mass[i] / (std::numbers::pi * spec.flying_grain_density));
    out.grains.add(sph.x[i], sph.y[i], sph.z[i], d, spec.flying_grain_density);
    out.grains.vx.back() = sph.vx[i];
    out.grains.vy.back() = sph.vy[i];
    out.grains.vz.back() = sph.vz[i];
    out.roles.push_back(static_cast<int>(GrainRole::flying));
  }

  balance.grains_moving = grain_totals(out.grains, out.roles, GrainRole::moving);
  balance.grains_frozen = grain_totals(out.grains, out.roles, GrainRole::frozen);
  balance.grains_flying = grain_totals(out.grains, out.roles, GrainRole::flying);
  for (std::size_t g = 0; g < out.grains.size(); ++g) {
    const double inertia = 0.1 * out.grains.mass(g) * out.grains.diameter[g] * out.grains.diameter[g];
    balance.grains_rotational_energy +=
        0.5 * inertia *
        (out.grains.omega_x[g] * out.grains.omega_x[g] + out.grains.omega_y[g] * out.grains.omega_y[g] +
         out.grains.omega_z[g] * out.grains.omega_z[g]);
  }
  return out;
}

}  // namespace craterkit::dem_late_stage
