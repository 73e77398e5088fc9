// The largest Mach number |v|/c of the moving particles (solver/mach_number.hpp): against hand-worked cases
// and a serial scan; ties go to the lowest index, whatever the thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

#include "craterkit/sph/particles/particles.hpp"
#include "craterkit/sph/solver/mach_number.hpp"

using namespace craterkit::sph;

namespace {

TEST(MachNumber, LargestOverActiveParticles) {
  // |v| = 5 (3-4-0) at c = 2 -> 2.5; |v| = 13 (12, 0, 5) at c = 4 -> 3.25 but ejected; |v| = 1 at c = 0.5
  // -> 2.
  const std::vector<double> vx{3.0, 12.0, 1.0, 0.0}, vy{4.0, 0.0, 0.0, 0.0}, vz{0.0, 5.0, 0.0, 0.0};
  const std::vector<double> c{2.0, 4.0, 0.5, 0.0};  // the last one is at rest with c = 0: Mach 0
  const std::vector<std::uint8_t> flags{particle_active, particle_ejected, particle_fixed, particle_active};
  const MachNumber m = max_mach_number(vx, vy, vz, c, flags);
  EXPECT_DOUBLE_EQ(m.value, 2.5);
  EXPECT_EQ(m.particle, 0u);
  const MachNumber all = max_mach_number(vx, vy, vz, c);  // no flags: every particle counts
  EXPECT_DOUBLE_EQ(all.value, 3.25);
  EXPECT_EQ(all.particle, 1u);
  EXPECT_EQ(max_mach_number({}, {}, {}, {}).value, 0.0);
  const std::vector<double> one{1.0}, zero{0.0};
  EXPECT_EQ(max_mach_number(one, zero, zero, zero).value, std::numeric_limits<double>::infinity());
  EXPECT_THROW(max_mach_number(one, zero, zero, std::vector<double>{}), std::invalid_argument);
  // Ties go to the lowest index, whatever the thread count.
  const std::vector<double> ones(1000, 1.0), zeros(1000, 0.0);
  const MachNumber tie = max_mach_number(zeros, ones, zeros, ones);
  EXPECT_EQ(tie.value, 1.0);
  EXPECT_EQ(tie.particle, 0u);
}

TEST(MachNumber, LargeSetMatchesASerialScan) {
  const std::size_t n = 100000;
  std::vector<double> vx(n), vy(n), vz(n), c(n);
  for (std::size_t i = 0; i < n; ++i) {
    vx[i] = std::sin(0.1 * static_cast<double>(i));
    vy[i] = std::cos(0.37 * static_cast<double>(i));
    vz[i] = 0.01 * static_cast<double>(i % 17);
    c[i] = 1.0 + static_cast<double>(i % 101);
  }
  double best = 0.0;
  std::size_t where = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double m = std::sqrt(vx[i] * vx[i] + vy[i] * vy[i] + vz[i] * vz[i]) / c[i];
    if (m > best) {
      best = m;
      where = i;
    }
  }
  const MachNumber m = max_mach_number(vx, vy, vz, c);
  EXPECT_NEAR(m.value, best, 1e-15 * best);
  EXPECT_EQ(m.particle, where);
}

}  // namespace
