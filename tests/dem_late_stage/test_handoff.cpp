// The hand-off from SPH particles to grains (dem_late_stage/handoff.hpp): what is carved, what moves how,
// what flies, what is frozen, and the balance it reports.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "craterkit/common/input_error.hpp"
#include "craterkit/dem_late_stage/handoff.hpp"

namespace craterkit::dem_late_stage {
namespace {

constexpr double rho = 1300.0;  // kg/m^3, the SPH target's bulk density
constexpr double dx = 0.2;      // m, SPH spacing
constexpr double extent = 4.0;  // m: SPH material and bed fill x, y in [0, 4]
constexpr double depth = 3.0;   // m below z = 0

template <class Velocity>
sph::Particles sph_half_space(Velocity&& velocity) {
  sph::Particles p;
  const int n = static_cast<int>(std::lround(extent / dx));
  const int nz = static_cast<int>(std::lround(depth / dx));
  p.resize(static_cast<std::size_t>(n * n * nz));
  std::size_t i = 0;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      for (int c = 0; c < nz; ++c, ++i) {
        p.id[i] = i + 1;
        p.x[i] = (a + 0.5) * dx;
        p.y[i] = (b + 0.5) * dx;
        p.z[i] = -(c + 0.5) * dx;
        const auto v = velocity(p.x[i], p.y[i], p.z[i]);
        p.vx[i] = v[0];
        p.vy[i] = v[1];
        p.vz[i] = v[2];
        p.mass[i] = rho * dx * dx * dx;
        p.density[i] = rho;
        p.smoothing_length[i] = 1.2 * dx;
      }
  return p;
}

// A cubic lattice of 0.28 m grains at 0.3 m from z = -3 m to z = +1 m (above the SPH surface).
dem::Grains lattice_bed() {
  dem::Grains bed;
  const double s = 0.3;
  for (double x = 0.15; x < extent; x += s)
    for (double y = 0.15; y < extent; y += s)
      for (double z = -depth + 0.15; z < 1.0; z += s) bed.add(x, y, z, 0.28, 2200.0);
  return bed;
}

HandoffSpec spec(bool quarter) {
  HandoffSpec s;
  s.bed_box = {0.0, extent, 0.0, extent, -depth, 1.0};
  s.frozen_thickness = 0.4;
  s.critical_density = 0.5 * rho;
  s.ejecta_speed = 0.5;
  s.flying_grain_density = 2200.0;
  s.quarter_symmetric = quarter;
  return s;
}

bool frozen_place(const HandoffSpec& s, double x, double y, double z) {
  return x > extent - s.frozen_thickness || y > extent - s.frozen_thickness ||
         z < -depth + s.frozen_thickness;
}

TEST(Handoff, CarvesTheBedAtTheSphSurfaceAndFreezesItsShell) {
  const auto s = spec(true);
  const auto out = hand_off(sph_half_space([](double, double, double) {
                              return std::array{0.0, 0.0, 0.0};
                            }),
                            lattice_bed(), s);
  std::size_t moving = 0;
  for (std::size_t g = 0; g < out.grains.size(); ++g) {
    const bool frozen = frozen_place(s, out.grains.x[g], out.grains.y[g], out.grains.z[g]);
    EXPECT_EQ(out.roles[g], static_cast<int>(frozen ? GrainRole::frozen : GrainRole::moving));
    // The half density surface of the SPH lattice lies within half a spacing of z = 0.
    if (!frozen) {
      EXPECT_LT(out.grains.z[g], 0.5 * dx);
    }
    moving += !frozen;
  }
  // Every grain deeper than a kernel support is kept; every one higher than a spacing is carved.
  const dem::Grains bed = lattice_bed();
  std::size_t deep = 0, high = 0;
  for (std::size_t g = 0; g < bed.size(); ++g) {
    if (frozen_place(s, bed.x[g], bed.y[g], bed.z[g])) continue;
    deep += bed.z[g] < -2.4 * dx;
    high += bed.z[g] > dx;
  }
  EXPECT_GE(moving, deep);
  EXPECT_GE(out.balance.grains_carved, high);
  EXPECT_EQ(out.balance.grains_moving.count, moving);
}

TEST(Handoff, AUniformFlowMovesEveryGrainWithItAndSpinsNone) {
  // Full domain: a flow across the mirror planes is not mirror symmetric.
  const std::array velocity{0.1, -0.2, -0.3};
  const auto s = spec(false);
  const auto out =
      hand_off(sph_half_space([&](double, double, double) { return velocity; }), lattice_bed(), s);
  ASSERT_GT(out.balance.grains_moving.count, 500u);
  for (std::size_t g = 0; g < out.grains.size(); ++g) {
    if (out.roles[g] != static_cast<int>(GrainRole::moving)) continue;
    EXPECT_NEAR(out.grains.vx[g], velocity[0], 1e-12);
    EXPECT_NEAR(out.grains.vy[g], velocity[1], 1e-12);
    EXPECT_NEAR(out.grains.vz[g], velocity[2], 1e-12);
    // The fit of a constant field: dv is rounding only.
    EXPECT_NEAR(out.grains.omega_x[g], 0.0, 1e-12);
    EXPECT_NEAR(out.grains.omega_y[g], 0.0, 1e-12);
    EXPECT_NEAR(out.grains.omega_z[g], 0.0, 1e-12);
  }
  // The balance: each side's momentum is its mass times the one velocity.
  const auto& b = out.balance;
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(b.grains_moving.momentum[k], b.grains_moving.mass * velocity[k], 1e-9 * b.grains_moving.mass);
    EXPECT_NEAR(b.sph_in_bed.momentum[k], b.sph_in_bed.mass * velocity[k], 1e-9 * b.sph_in_bed.mass);
  }
  EXPECT_LT(b.grains_rotational_energy, 1e-20 * b.grains_moving.kinetic_energy);
  EXPECT_EQ(b.sph_outside_bed.count, 0u);
  EXPECT_NEAR(b.max_moving_speed, std::sqrt(0.14), 1e-12);
}

TEST(Handoff, ARigidRotationSpinsEveryGrainAtItsAngularVelocity) {
  // v = w x r about a vertical axis through (2, 2): curl v / 2 = w, exact for a linear field wherever the
  // neighbours span three dimensions (away from the surface and the sides).
  const double w = 0.05;  // rad/s
  const auto s = spec(false);
  const auto out = hand_off(sph_half_space([&](double x, double y, double) {
                              return std::array{-w * (y - 2.0), w * (x - 2.0), 0.0};
                            }),
                            lattice_bed(), s);
  std::size_t checked = 0;
  for (std::size_t g = 0; g < out.grains.size(); ++g) {
    if (out.roles[g] != static_cast<int>(GrainRole::moving)) continue;
    const double x = out.grains.x[g], y = out.grains.y[g], z = out.grains.z[g];
    if (x < 0.6 || y < 0.6 || x > extent - 1.0 || y > extent - 1.0 || z > -0.6 || z < -depth + 1.0) continue;
    EXPECT_NEAR(out.grains.omega_z[g], w, 1e-9 * w);
    EXPECT_NEAR(out.grains.omega_x[g], 0.0, 1e-9 * w);
    EXPECT_NEAR(out.grains.omega_y[g], 0.0, 1e-9 * w);
    // The weighted mean of a linear field is its value at the neighbours' weighted centroid, within a
    // spacing.
    EXPECT_NEAR(out.grains.vx[g], -w * (y - 2.0), w * dx);
    ++checked;
  }
  EXPECT_GT(checked, 100u);
  EXPECT_GT(out.balance.grains_rotational_energy, 0.0);
}

TEST(Handoff, FastRisingEjectaFlyAsGrainsOfTheirOwnMassAndTheRestStays) {
  auto sph = sph_half_space([](double, double, double) { return std::array{0.0, 0.0, 0.0}; });
  const std::size_t n = sph.size();
  sph.resize(n + 4);
  const double m = rho * dx * dx * dx;
  // Rising fast above the plane: flies. Falling fast: stays (it will hit the surface). Rising slowly:
  // stays. Already ejected by the SPH run: not handed over.
  const std::array<std::array<double, 6>, 4> particles{{{1.0, 1.0, 2.0, 0.3, 0.0, 0.8},
                                                        {1.5, 1.0, 2.0, 0.0, 0.0, -0.8},
                                                        {2.0, 1.0, 2.0, 0.0, 0.0, 0.3},
                                                        {2.5, 1.0, 2.0, 0.0, 0.0, 5.0}}};
  for (std::size_t k = 0; k < 4; ++k) {
    const std::size_t i = n + k;
    sph.id[i] = i + 1;
    sph.x[i] = particles[k][0];
    sph.y[i] = particles[k][1];
    sph.z[i] = particles[k][2];
    sph.vx[i] = particles[k][3];
    sph.vy[i] = particles[k][4];
    sph.vz[i] = particles[k][5];
    sph.mass[i] = m;
    sph.density[i] = rho;
    sph.smoothing_length[i] = 1.2 * dx;
  }
  sph.flags[n + 3] = sph::particle_ejected;
  const auto out = hand_off(sph, lattice_bed(), spec(true));
  const auto& b = out.balance;
  EXPECT_EQ(b.sph_ejected.count, 1u);
  EXPECT_DOUBLE_EQ(b.sph_ejected.momentum[2], 5.0 * m);
  ASSERT_EQ(b.sph_flying.count, 1u);
  ASSERT_EQ(b.grains_flying.count, 1u);
  EXPECT_DOUBLE_EQ(b.grains_flying.mass, m);
  EXPECT_DOUBLE_EQ(b.grains_flying.momentum[0], 0.3 * m);
  EXPECT_DOUBLE_EQ(b.grains_flying.momentum[2], 0.8 * m);
  EXPECT_NEAR(b.grains_flying.kinetic_energy, b.sph_flying.kinetic_energy,
              1e-12 * b.sph_flying.kinetic_energy);
  const std::size_t last = out.grains.size() - 1;
  EXPECT_EQ(out.roles[last], static_cast<int>(GrainRole::flying));
  EXPECT_DOUBLE_EQ(out.grains.x[last], 1.0);
  EXPECT_DOUBLE_EQ(out.grains.z[last], 2.0);
  // The two that stay flow on, but above the bed's box they are not handed over: the balance says so.
  EXPECT_EQ(b.sph_in_bed.count, n);
  EXPECT_EQ(b.sph_outside_bed.count, 2u);
  EXPECT_DOUBLE_EQ(b.sph_outside_bed.momentum[2], -0.5 * m);
}

TEST(Handoff, RefusesASpecOutOfRangeNamingTheField) {
  auto s = spec(true);
  s.ejecta_speed = 0.0;
  try {
    (void)hand_off(sph::Particles{}, dem::Grains{}, s);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("handoff.ejecta_speed"), std::string::npos) << e.what();
  }
  s = spec(true);
  s.bed_box.x_low = -1.0;
  EXPECT_THROW((void)hand_off(sph::Particles{}, dem::Grains{}, s), InputError);
}

}  // namespace
}  // namespace craterkit::dem_late_stage
