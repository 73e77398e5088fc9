// Particles that crossed a mirror plane are reflected back (mirror_reflection.hpp): position mirrored,
// the odd vector and tensor components negated, everything else untouched; fixed and ejected particles,
// particles on the right side and boxes without mirrors are left alone.
#include <gtest/gtest.h>

#include "craterkit/sph/neighbours/mirror_reflection.hpp"

namespace craterkit::sph {
namespace {

// Particle k gets distinct values in every field, so that a swapped or missed component shows.
Particles sample(std::size_t n) {
  Particles p;
  p.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double k = static_cast<double>(i + 1);
    p.vx[i] = 1 * k, p.vy[i] = 2 * k, p.vz[i] = 3 * k;
    p.acceleration_x[i] = 4 * k, p.acceleration_y[i] = 5 * k, p.acceleration_z[i] = 6 * k;
    p.stress_xx[i] = 7 * k, p.stress_xy[i] = 8 * k, p.stress_xz[i] = 9 * k, p.stress_yy[i] = 10 * k,
    p.stress_yz[i] = 11 * k;
    p.stress_rate_xx[i] = 12 * k, p.stress_rate_xy[i] = 13 * k, p.stress_rate_xz[i] = 14 * k,
    p.stress_rate_yy[i] = 15 * k, p.stress_rate_yz[i] = 16 * k;
    p.density[i] = 17 * k, p.pressure[i] = 18 * k;
  }
  return p;
}

TEST(MirrorReflection, ParticlesAcrossThePlanesComeBackWithOddComponentsNegated) {
  Box box;
  box.lower = {1.0, -2.0, 0.0};
  box.mirror = {true, true, false};
  Particles p = sample(5);
  // 0: inside; 1: across x = 1; 2: across y = -2; 3: across both; 4: across x but fixed.
  const double xs[5] = {1.5, 0.25, 3.0, 0.5, 0.0}, ys[5] = {-1.0, 4.0, -2.5, -3.0, 0.0};
  for (std::size_t i = 0; i < 5; ++i) p.x[i] = xs[i], p.y[i] = ys[i], p.z[i] = -1.0;
  p.flags[4] = particle_fixed;
  const Particles before = p;
  EXPECT_EQ(reflect_across_mirror_planes(p, box), 4u);  // 1, 2, and 3 twice
  EXPECT_EQ(p.x[0], 1.5);
  EXPECT_EQ(p.vx[0], before.vx[0]);
  EXPECT_EQ(p.x[1], 1.75);  // 2 x 1 - 0.25
  EXPECT_EQ(p.y[1], 4.0);
  EXPECT_EQ(p.vx[1], -before.vx[1]);
  EXPECT_EQ(p.vy[1], before.vy[1]);
  EXPECT_EQ(p.acceleration_x[1], -before.acceleration_x[1]);
  EXPECT_EQ(p.stress_xy[1], -before.stress_xy[1]);
  EXPECT_EQ(p.stress_xz[1], -before.stress_xz[1]);
  EXPECT_EQ(p.stress_yz[1], before.stress_yz[1]);
  EXPECT_EQ(p.stress_rate_xy[1], -before.stress_rate_xy[1]);
  EXPECT_EQ(p.stress_rate_xz[1], -before.stress_rate_xz[1]);
  EXPECT_EQ(p.stress_xx[1], before.stress_xx[1]);
  EXPECT_EQ(p.y[2], -1.5);  // 2 x (-2) + 2.5
  EXPECT_EQ(p.vy[2], -before.vy[2]);
  EXPECT_EQ(p.acceleration_y[2], -before.acceleration_y[2]);
  EXPECT_EQ(p.stress_xy[2], -before.stress_xy[2]);
  EXPECT_EQ(p.stress_yz[2], -before.stress_yz[2]);
  EXPECT_EQ(p.stress_xz[2], before.stress_xz[2]);
  EXPECT_EQ(p.stress_rate_yz[2], -before.stress_rate_yz[2]);
  // Both planes: x and y components negated, S_xy twice (back to itself), S_xz and S_yz once.
  EXPECT_EQ(p.x[3], 1.5);
  EXPECT_EQ(p.y[3], -1.0);
  EXPECT_EQ(p.vx[3], -before.vx[3]);
  EXPECT_EQ(p.vy[3], -before.vy[3]);
  EXPECT_EQ(p.vz[3], before.vz[3]);
  EXPECT_EQ(p.stress_xy[3], before.stress_xy[3]);
  EXPECT_EQ(p.stress_xz[3], -before.stress_xz[3]);
  EXPECT_EQ(p.stress_yz[3], -before.stress_yz[3]);
  EXPECT_EQ(p.x[4], 0.0);  // fixed: left alone
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(p.z[i], -1.0);
    EXPECT_EQ(p.density[i], before.density[i]);
    EXPECT_EQ(p.pressure[i], before.pressure[i]);
    EXPECT_EQ(p.stress_yy[i], before.stress_yy[i]);
  }
  // Reflected once, nothing is left to reflect.
  EXPECT_EQ(reflect_across_mirror_planes(p, box), 0u);
  Box plain;  // no mirrors: nothing moves
  Particles q = before;
  EXPECT_EQ(reflect_across_mirror_planes(q, plain), 0u);
  EXPECT_EQ(q.x[1], 0.25);
}

}  // namespace
}  // namespace craterkit::sph
