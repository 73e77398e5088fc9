// Pair loops with mirror planes: a random cloud in the quarter x > 0, y > 0 with mirror planes x = 0 and
// y = 0 gives, for every particle, the rates of the explicitly reflected full cloud (four times the
// particles, no mirrors): accelerations, density, energy and viscosity-alpha rates, the corrected velocity
// gradient (solid, random deviatoric stresses) and the summed density, to round-off.
// And the rate pass's four lanes (rates.cpp): the AVX2 and the baseline build give the same rates bit for
// bit, and so do neighbour lists that hold more than the pairs within the support (a skin).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "craterkit/sph/neighbours/neighbour_search.hpp"
#include "craterkit/sph/particles/mirror_image.hpp"
#include "craterkit/sph/rates/gradient_correction.hpp"
#include "craterkit/sph/rates/rates.hpp"
#include "craterkit/sph/rates/summation_density.hpp"

using namespace craterkit::sph;

namespace {

// Round-off bound: the sums run over ~60 terms of order one in a different order in the two clouds.
constexpr double tolerance = 1e-12;

struct Cloud {
  Particles p;
  NeighbourLists lists;
  RateWorkspace workspace;
  Box box;
};

void finish(Cloud& c, double skin) {
  c.workspace.inverse_density.resize(c.p.size());
  c.workspace.volume.resize(c.p.size());
  for (std::size_t k = 0; k < c.p.size(); ++k) {
    c.workspace.inverse_density[k] = 1.0 / c.p.density[k];
    c.workspace.volume[k] = c.p.mass[k] / c.p.density[k];
  }
  NeighbourSearch search({skin, 16});
  search.build(neighbour_input(c.p), c.box, c.lists);
}

// A jittered n^3 lattice of spacing 1 in the quarter (nodes at a + 1/2, so the nearest lie 0.2-0.8 from
// the planes) with random states; random deviatoric stresses.
Cloud quarter_cloud(int n, unsigned seed) {
  Cloud c;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  c.p.resize(static_cast<std::size_t>(n) * n * n);
  std::size_t i = 0;
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      for (int d = 0; d < n; ++d, ++i) {
        c.p.id[i] = i;
        c.p.x[i] = a + 0.5 + 0.3 * u(rng);
        c.p.y[i] = b + 0.5 + 0.3 * u(rng);
        c.p.z[i] = d + 0.3 * u(rng);
        c.p.mass[i] = 1.0 + 0.3 * u(rng);
        c.p.density[i] = 1.0 + 0.2 * u(rng);
        c.p.smoothing_length[i] = 1.2 + 0.2 * u(rng);
        c.p.vx[i] = u(rng);
        c.p.vy[i] = u(rng);
        c.p.vz[i] = u(rng);
        c.p.pressure[i] = 1.0 + 0.5 * u(rng);
        c.p.sound_speed[i] = 1.0 + 0.5 * u(rng);
        c.p.specific_energy[i] = 1.0;
        c.p.viscosity_alpha[i] = 0.5 + 0.4 * u(rng);
        c.p.stress_xx[i] = 0.3 * u(rng);
        c.p.stress_xy[i] = 0.3 * u(rng);
        c.p.stress_xz[i] = 0.3 * u(rng);
        c.p.stress_yy[i] = 0.3 * u(rng);
        c.p.stress_yz[i] = 0.3 * u(rng);
      }
    }
  }
  c.box.lower = {0.0, 0.0, 0.0};
  c.box.upper = {double(n), double(n), double(n)};
  return c;
}

// The full cloud: every quarter particle i and its reflections written out explicitly, copy s (sign
// (sx, sy) = (+,+), (-,+), (+,-), (-,-)) at index s n + i; velocities and the off-diagonal stresses that
// change sign under each reflection (S_xy with sx sy, S_xz with sx, S_yz with sy). No mirrors.
Cloud reflected_full_cloud(const Cloud& q) {
  Cloud c;
  const std::size_t n = q.p.size();
  c.p.resize(4 * n);
  for (std::size_t s = 0; s < 4; ++s) {
    const double sx = (s & 1) ? -1.0 : 1.0, sy = (s & 2) ? -1.0 : 1.0;
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t k = s * n + i;
      c.p.id[k] = k;
      c.p.x[k] = sx * q.p.x[i];
      c.p.y[k] = sy * q.p.y[i];
      c.p.z[k] = q.p.z[i];
      c.p.vx[k] = sx * q.p.vx[i];
      c.p.vy[k] = sy * q.p.vy[i];
      c.p.vz[k] = q.p.vz[i];
      c.p.stress_xx[k] = q.p.stress_xx[i];
      c.p.stress_yy[k] = q.p.stress_yy[i];
      c.p.stress_xy[k] = sx * sy * q.p.stress_xy[i];
      c.p.stress_xz[k] = sx * q.p.stress_xz[i];
      c.p.stress_yz[k] = sy * q.p.stress_yz[i];
      for (auto field : {&Particles::mass, &Particles::density, &Particles::smoothing_length,
                         &Particles::pressure, &Particles::sound_speed, &Particles::specific_energy,
                         &Particles::viscosity_alpha, &Particles::distention}) {
        (c.p.*field)[k] = (q.p.*field)[i];
      }
    }
  }
  return c;
}

// |quarter - full| <= tolerance x (largest |full| of the field over the particles), for the first n
// particles of the full cloud (the unreflected copy). Returns the largest relative difference.
// "name k". Built by appending: GCC 12 warns falsely (-Warray-bounds) on "literal" + std::to_string(k) here
// when GoogleTest comes from the precompiled header.
std::string indexed_name(const char* name, int k) {
  std::string out = name;
  out += ' ';
  out += std::to_string(k);
  return out;
}

double compare(const std::string& name, const std::vector<double>& quarter, const std::vector<double>& full) {
  const std::size_t n = quarter.size();
  double scale = 0.0;
  for (std::size_t i = 0; i < n; ++i) scale = std::max(scale, std::abs(full[i]));
  double worst = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double difference = std::abs(quarter[i] - full[i]) / scale;
    worst = std::max(worst, difference);
    EXPECT_LE(difference, tolerance) << name << " of particle " << i << ": " << quarter[i] << " vs "
                                     << full[i];
  }
  EXPECT_GT(scale, 0.0) << name;
  return worst;
}

struct Rates {
  std::vector<double> ax, ay, az, drho, du, dalpha, density;
  std::array<std::vector<double>, 9> gradient;
  std::array<std::vector<double>, 6> correction;
  std::vector<std::uint32_t> neighbours;
};

Rates evaluate(Cloud& c, const RateOptions& options) {
  VelocityGradients g;
  if (options.solid) {
    compute_correction_matrices(c.p, PairList{c.lists.offsets, c.lists.neighbours}, options, c.workspace,
                                ParticleSelection::all(c.p.size()));
  }
  compute_rates(c.p, PairList{c.lists.offsets, c.lists.neighbours}, options, c.workspace,
                options.solid ? &g : nullptr);
  Rates r{c.p.acceleration_x,
          c.p.acceleration_y,
          c.p.acceleration_z,
          c.p.density_rate,
          c.p.energy_rate,
          c.p.viscosity_alpha_rate,
          {},
          {},
          {},
          c.workspace.neighbour_count};
  if (options.solid) {
    r.gradient = g.corrected;
    r.correction = {c.p.correction_xx, c.p.correction_xy, c.p.correction_xz,
                    c.p.correction_yy, c.p.correction_yz, c.p.correction_zz};
  }
  Particles summed = c.p;
  compute_summation_density(summed, PairList{c.lists.offsets, c.lists.neighbours}, options.kernel,
                            options.period, options.mirror, options.wide_lanes);
  r.density = summed.density;
  return r;
}

RateOptions options_for(bool solid, KernelType kernel) {
  RateOptions options;
  options.kernel = kernel;
  options.solid = solid;
  options.gravity = {0.1, -0.2, -1.0};
  options.viscosity.viscosity_switch = ViscositySwitch::morris_monaghan;
  return options;
}

void expect_quarter_equals_full(bool solid, KernelType kernel, double skin) {
  Cloud quarter = quarter_cloud(6, 21);
  quarter.box.mirror = {true, true, false};
  Cloud full = reflected_full_cloud(quarter);
  finish(quarter, skin);
  finish(full, skin);
  RateOptions options = options_for(solid, kernel);
  const Rates f = evaluate(full, options);
  options.mirror = mirror_planes(quarter.box);
  const Rates q = evaluate(quarter, options);
  const std::size_t n = quarter.p.size();
  const auto first = [n](const std::vector<double>& v) {
    return std::vector<double>(v.begin(), v.begin() + n);
  };
  double worst = 0.0;
  worst = std::max(worst, compare("acceleration_x", q.ax, first(f.ax)));
  worst = std::max(worst, compare("acceleration_y", q.ay, first(f.ay)));
  worst = std::max(worst, compare("acceleration_z", q.az, first(f.az)));
  worst = std::max(worst, compare("density_rate", q.drho, first(f.drho)));
  worst = std::max(worst, compare("energy_rate", q.du, first(f.du)));
  worst = std::max(worst, compare("viscosity_alpha_rate", q.dalpha, first(f.dalpha)));
  worst = std::max(worst, compare("summation density", q.density, first(f.density)));
  if (solid) {
    for (int k = 0; k < 9; ++k) {
      worst = std::max(worst,
                       compare(indexed_name("corrected gradient", k), q.gradient[k], first(f.gradient[k])));
    }
    for (int k = 0; k < 6; ++k) {
      worst = std::max(
          worst, compare(indexed_name("correction matrix", k), q.correction[k], first(f.correction[k])));
    }
  }
  // The same interacting neighbours (the count drives the smoothing length).
  for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(q.neighbours[i], f.neighbours[i]) << "particle " << i;
  std::printf(
      "quarter vs reflected full cloud (%s, %s, skin %.2g): largest difference %.2e of the field's "
      "largest magnitude\n",
      solid ? "solid" : "fluid", std::string(kernel_name(kernel)).c_str(), skin, worst);
}

}  // namespace

TEST(MirrorRates, SolidQuarterEqualsTheReflectedFullCloud) {
  expect_quarter_equals_full(true, KernelType::cubic_spline, 0.0);
}

TEST(MirrorRates, FluidQuarterEqualsTheReflectedFullCloudWithSkinAndWendland) {
  expect_quarter_equals_full(false, KernelType::cubic_spline, 0.1);
  expect_quarter_equals_full(true, KernelType::wendland_c2, 0.1);
}

TEST(MirrorRates, WithoutTheMirrorsTheQuarterDiffers) {
  // The test above can fail: the same quarter without mirror planes has free surfaces at x = 0, y = 0.
  Cloud quarter = quarter_cloud(6, 21);
  Cloud full = reflected_full_cloud(quarter);
  finish(quarter, 0.0);
  finish(full, 0.0);
  const RateOptions options = options_for(true, KernelType::cubic_spline);
  const Rates f = evaluate(full, options);
  const Rates q = evaluate(quarter, options);
  double largest = 0.0;
  for (std::size_t i = 0; i < quarter.p.size(); ++i) largest = std::max(largest, std::abs(q.ax[i] - f.ax[i]));
  EXPECT_GT(largest, 0.1);
}

TEST(MirrorRates, MirroredMomentumSumsOnlyAlongTheUnmirroredAxis) {
  // In a quarter the planes push back: x and y momentum of the quarter are not conserved by the pair forces,
  // z momentum is (gravity off). Sum over the quarter of m a_z vanishes to round-off.
  Cloud quarter = quarter_cloud(6, 22);
  quarter.box.mirror = {true, true, false};
  finish(quarter, 0.0);
  RateOptions options = options_for(true, KernelType::cubic_spline);
  options.gravity = {0.0, 0.0, 0.0};
  options.mirror = mirror_planes(quarter.box);
  evaluate(quarter, options);
  double pz = 0.0, px = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < quarter.p.size(); ++i) {
    pz += quarter.p.mass[i] * quarter.p.acceleration_z[i];
    px += quarter.p.mass[i] * quarter.p.acceleration_x[i];
    scale += quarter.p.mass[i] * std::abs(quarter.p.acceleration_z[i]);
  }
  EXPECT_LT(std::abs(pz), 1e-13 * scale);
  EXPECT_GT(std::abs(px), 1e-3 * scale);
}

namespace {

// Every list sorted by entry, as the kept lists of the block steps are.
void sort_lists(NeighbourLists& lists) {
  for (std::size_t i = 0; i + 1 < lists.offsets.size(); ++i) {
    std::sort(lists.neighbours.begin() + std::ptrdiff_t(lists.offsets[i]),
              lists.neighbours.begin() + std::ptrdiff_t(lists.offsets[i + 1]));
  }
}

void expect_bitwise_equal(const Rates& a, const Rates& b, bool solid) {
  const auto same = [](const char* name, const std::vector<double>& x, const std::vector<double>& y) {
    ASSERT_EQ(x.size(), y.size()) << name;
    std::size_t differing = 0;
    for (std::size_t i = 0; i < x.size(); ++i) differing += x[i] == y[i] ? 0 : 1;  // (no NaN here)
    EXPECT_EQ(differing, 0u) << name;
  };
  same("acceleration_x", a.ax, b.ax);
  same("acceleration_y", a.ay, b.ay);
  same("acceleration_z", a.az, b.az);
  same("density_rate", a.drho, b.drho);
  same("energy_rate", a.du, b.du);
  same("viscosity_alpha_rate", a.dalpha, b.dalpha);
  same("summation density", a.density, b.density);  // the other pass in lanes
  if (solid) {
    for (int k = 0; k < 9; ++k) same("corrected gradient", a.gradient[k], b.gradient[k]);
    for (int k = 0; k < 6; ++k) same("correction matrix", a.correction[k], b.correction[k]);
  }
  EXPECT_EQ(a.neighbours, b.neighbours);
}

// Mirrors, the switch, the Balsara factor and (solids) the artificial stress: every branch of the lanes.
RateOptions lane_options(bool solid) {
  RateOptions options = options_for(solid, KernelType::cubic_spline);
  options.viscosity.balsara = true;
  if (solid) options.artificial_stress.epsilon = 0.3;
  return options;
}

}  // namespace

TEST(RateLanes, WideAndBaselineLanesGiveTheSameRatesBitForBit) {
  for (const bool solid : {false, true}) {
    Cloud quarter = quarter_cloud(6, 23);
    quarter.box.mirror = {true, true, false};
    finish(quarter, 0.1);
    Cloud copy = quarter;  // each evaluation from the same state (the pass writes the Balsara factors)
    RateOptions options = lane_options(solid);
    options.mirror = mirror_planes(quarter.box);
    const Rates wide = evaluate(quarter, options);
    options.wide_lanes = false;
    const Rates baseline = evaluate(copy, options);
    expect_bitwise_equal(wide, baseline, solid);
  }
}

TEST(RateLanes, ListsWithASkinGiveTheSameRatesBitForBit) {
  // The pairs beyond the support are dropped before the lanes take the pairs four at a time, so a list
  // sorted by entry gives the same sums whatever superset it holds (restarts rebuild the lists).
  for (const bool solid : {false, true}) {
    Cloud exact = quarter_cloud(6, 24);
    exact.box.mirror = {true, true, false};
    Cloud skinned = exact;
    finish(exact, 0.0);
    finish(skinned, 0.3);
    sort_lists(exact.lists);
    sort_lists(skinned.lists);
    ASSERT_GT(skinned.lists.neighbours.size(), exact.lists.neighbours.size() + exact.p.size());
    RateOptions options = lane_options(solid);
    options.mirror = mirror_planes(exact.box);
    expect_bitwise_equal(evaluate(exact, options), evaluate(skinned, options), solid);
  }
}
