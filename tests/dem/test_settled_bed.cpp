// A bed settled under gravity by LAMMPS (docs/dem.md, "Settled bed"): at rest, packed as frictional spheres
// pack, holding every grain it was cut to, in vertical equilibrium, and cached.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

#include "craterkit/dem/granular_bed.hpp"
#include "sph_core/test_io_scratch_directory.hpp"

namespace craterkit::dem {
namespace {

BedSpec small_bed() {
  BedSpec spec;
  spec.grain_sizes = {0.009, 0.011};  // +-10 %
  spec.length_x = 0.12;
  spec.length_y = 0.12;
  spec.depth = 0.10;
  spec.contact.sliding_friction = 0.5;
  spec.contact.rolling_friction = 0.1;
  return spec;
}

TEST(SettledBed, RestsAtTheDepthPackedAsFrictionalSpheresPack) {
  const test::ScratchDirectory folder("dem");
  const BedSpec spec = small_bed();
  const SettledBed bed = settle_bed(spec, folder.path());
  ASSERT_GT(bed.grains.size(), 1000U);
  // At rest: mean speed under the requested 1e-3 sqrt(g d).
  double speed_sum = 0;
  for (std::size_t i = 0; i < bed.grains.size(); ++i)
    speed_sum += std::sqrt(bed.grains.vx[i] * bed.grains.vx[i] + bed.grains.vy[i] * bed.grains.vy[i] +
                           bed.grains.vz[i] * bed.grains.vz[i]);
  EXPECT_LT(speed_sum / static_cast<double>(bed.grains.size()),
            1e-3 * std::sqrt(spec.gravity * spec.grain_sizes.mean_diameter()));
  // The surface within a grain of the depth (grains with centres above it were removed, then it settled).
  EXPECT_NEAR(bed.surface_height, spec.depth, spec.grain_sizes.max_diameter);
  // Frictional spheres poured under gravity pack between random loose packing (0.55, Onoda & Liniger 1990,
  // Phys. Rev. Lett. 64, 2727) and random close packing (0.64, Scott & Kilgour 1969, J. Phys. D 2, 863);
  // a +-10 % size spread raises the close limit by under 0.01.
  EXPECT_GT(bed.packing_fraction, 0.55);
  EXPECT_LT(bed.packing_fraction, 0.65);
  EXPECT_NEAR(bed.bulk_density, bed.packing_fraction * spec.grain_density, 1e-9);
  // Every grain inside the periodic box and above the floor.
  for (std::size_t i = 0; i < bed.grains.size(); ++i) {
    EXPECT_GE(bed.grains.x[i], 0.0);
    EXPECT_LT(bed.grains.x[i], spec.length_x);
    EXPECT_GT(bed.grains.z[i], 0.4 * bed.grains.diameter[i]);
  }
  std::printf("settled bed: %zu grains, surface %.4f m, packing fraction %.4f, bulk density %.1f kg/m^3\n",
              bed.grains.size(), bed.surface_height, bed.packing_fraction, bed.bulk_density);

  // The contacts carry the bed's weight as Hertz overlaps: the mean overlap of the grains in the middle slab
  // (z from 0.4 to 0.6 of the depth), put into youngs_modulus_for_overlap with the slab's depth below the
  // surface, gives back the modulus the bed was settled with (a mean-field relation: within 25 %, i.e. the
  // overlaps within about 15 %).
  const auto& g = bed.grains;
  double overlap_sum = 0;
  int contacts = 0;
  for (std::size_t i = 0; i < g.size(); ++i) {
    if (g.z[i] < 0.4 * spec.depth || g.z[i] >= 0.6 * spec.depth) continue;
    for (std::size_t j = 0; j < g.size(); ++j) {
      if (j == i) continue;
      double dx = g.x[j] - g.x[i];
      double dy = g.y[j] - g.y[i];
      dx -= spec.length_x * std::round(dx / spec.length_x);
      dy -= spec.length_y * std::round(dy / spec.length_y);
      const double dz = g.z[j] - g.z[i];
      const double overlap = 0.5 * (g.diameter[i] + g.diameter[j]) - std::sqrt(dx * dx + dy * dy + dz * dz);
      if (overlap > 0) {
        overlap_sum += overlap / g.diameter[i];
        ++contacts;
      }
    }
  }
  ASSERT_GT(contacts, 500);
  const double mean_overlap = overlap_sum / contacts;
  const double modulus = youngs_modulus_for_overlap(
      bed.bulk_density, spec.grain_density, spec.gravity, bed.surface_height - 0.5 * spec.depth,
      spec.grain_sizes.mean_diameter(), spec.contact.poisson_ratio, mean_overlap);
  std::printf(
      "middle slab: %d contacts, mean overlap %.3e d -> Young's modulus %.3e Pa (settled with %.3e)\n",
      contacts, mean_overlap, modulus, spec.contact.youngs_modulus);
  EXPECT_NEAR(modulus / spec.contact.youngs_modulus, 1.0, 0.25);
}

TEST(SettledBed, IsCachedUnderItsKeyAndReadBackUnchanged) {
  const test::ScratchDirectory folder("dem");
  BedSpec spec = small_bed();
  spec.length_x = spec.length_y = 0.06;
  spec.depth = 0.05;
  const auto start = std::chrono::steady_clock::now();
  const SettledBed first = settled_bed_cached(spec, folder.path());
  const double settle_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto dump = folder.path() / ("bed-" + bed_hash(spec) + ".dump");
  ASSERT_TRUE(std::filesystem::exists(dump));
  const auto written = std::filesystem::last_write_time(dump);
  // The settling folder is removed: a second call must come from the cache, not from LAMMPS.
  std::filesystem::remove_all(folder.path() / ("bed-" + bed_hash(spec)));
  const SettledBed second = settled_bed_cached(spec, folder.path());
  EXPECT_EQ(std::filesystem::last_write_time(dump), written);
  EXPECT_FALSE(std::filesystem::exists(folder.path() / ("bed-" + bed_hash(spec))));
  ASSERT_EQ(second.grains.size(), first.grains.size());
  for (std::size_t i = 0; i < first.grains.size(); ++i) {
    EXPECT_EQ(second.grains.z[i], first.grains.z[i]);
    EXPECT_EQ(second.grains.diameter[i], first.grains.diameter[i]);
  }
  EXPECT_EQ(second.packing_fraction, first.packing_fraction);
  // Another bed (another seed) is settled anew beside it.
  spec.seed = 2;
  const SettledBed other = settled_bed_cached(spec, folder.path());
  EXPECT_TRUE(std::filesystem::exists(folder.path() / ("bed-" + bed_hash(spec) + ".dump")));
  EXPECT_NE(other.grains.z[0], first.grains.z[0]);
  std::printf("settling took %.1f s\n", settle_seconds);
}

}  // namespace
}  // namespace craterkit::dem
