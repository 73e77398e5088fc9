// drift_time_within (integrator.hpp): the time for which drift() keeps a particle within a given room is a
// bound, checked by drifting particles with random velocities, accelerations and expanding or compressing
// densities through many substeps up to it; and it is not needlessly loose where the motion is simple.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "craterkit/sph/integration/integrator.hpp"

namespace craterkit::sph {
namespace {

TEST(DriftBound, NoParticleLeavesItsRoomWithinTheBound) {
  std::mt19937_64 random(20261207);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  constexpr std::size_t n = 2000;
  Particles p;
  p.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    p.x[i] = 10.0 * unit(random);
    p.y[i] = 10.0 * unit(random);
    p.z[i] = 10.0 * unit(random);
    p.vx[i] = 3.0 * unit(random);
    p.vy[i] = 3.0 * unit(random);
    p.vz[i] = (i % 5 == 0) ? 0.0 : 3.0 * unit(random);
    p.acceleration_x[i] = 50.0 * unit(random);
    p.acceleration_y[i] = 50.0 * unit(random);
    p.acceleration_z[i] = 50.0 * unit(random);
    p.mass[i] = 1.0;
    p.density[i] = 1000.0 * (1.0 + 0.5 * unit(random));
    p.density_rate[i] = 2.0e4 * unit(random);  // expanding (h grows) for half of them
    p.smoothing_length[i] = 0.05 * (1.5 + unit(random));
  }
  const Particles start = p;
  std::vector<double> room(n), bound(n);
  for (std::size_t i = 0; i < n; ++i) {
    room[i] = 0.01 * (1.5 + unit(random));
    bound[i] = drift_time_within(p, i, room[i]);
    ASSERT_GT(bound[i], 0.0) << i;
  }
  // Drift everyone in 200 uneven substeps to the largest bound; check each particle while within its bound.
  const double end = *std::max_element(bound.begin(), bound.end());
  double t = 0.0, tightest = 0.0;
  for (int k = 0; k < 200; ++k) {
    const double dt = end / 200.0 * (k % 3 == 0 ? 0.5 : 1.25);
    drift(p, dt, Box{}, SmoothingLengthParameters{});
    t += dt;
    for (std::size_t i = 0; i < n; ++i) {
      if (!(t < bound[i])) continue;
      const double dx = p.x[i] - start.x[i], dy = p.y[i] - start.y[i], dz = p.z[i] - start.z[i];
      const double used = std::sqrt(dx * dx + dy * dy + dz * dz) +
                          std::max(0.0, p.smoothing_length[i] - start.smoothing_length[i]);
      ASSERT_LE(used, room[i]) << "particle " << i << " at t = " << t << " of its bound " << bound[i];
      tightest = std::max(tightest, used / room[i]);
    }
  }
  // Not vacuous: some particles come close to their room within their bound.
  EXPECT_GT(tightest, 0.3);
}

TEST(DriftBound, UniformMotionUsesHalfTheRoomForThePath) {
  Particles p;
  p.resize(1);
  p.vx[0] = 2.0;
  p.mass[0] = 1.0;
  p.density[0] = 1000.0;
  p.smoothing_length[0] = 0.1;
  // Half the room (0.02 m) for the path at 2 m/s, less the rounding allowance (1e-12 of |x| + h).
  EXPECT_NEAR(drift_time_within(p, 0, 0.04), 0.01, 1e-12);
  p.vx[0] = 0.0;
  EXPECT_EQ(drift_time_within(p, 0, 0.04), std::numeric_limits<double>::infinity());  // at rest
  p.density_rate[0] = -1000.0;  // expanding by a tenth per second: h grows
  const double ratio = 1.0 + 0.02 / 0.1;
  EXPECT_NEAR(drift_time_within(p, 0, 0.04), (1.0 - 1.0 / (ratio * ratio * ratio)) / 1.0, 1e-9);
  EXPECT_EQ(drift_time_within(p, 0, 0.0), 0.0);
  EXPECT_EQ(drift_time_within(p, 0, -1.0), 0.0);
}

}  // namespace
}  // namespace craterkit::sph
