// Piles of DEM grains whose contact friction was derived from an angle of repose stand at that angle
// (docs/dem.md, "Angle of repose"; docs/validation.md, "DEM piles"): the targets of the SPH granular tests,
// theta(f) +- 3 degrees for f = 0.55 and 0.7, on piles of another seed than the calibration's.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "craterkit/dem/column_collapse.hpp"
#include "craterkit/dem/repose_calibration.hpp"
#include "sph_core/test_io_scratch_directory.hpp"

namespace craterkit::dem {
namespace {

// theta(f) of the SPH material: f = 2 sqrt(2) sin(theta) / (3 - sin(theta)) (Luther et al. 2022) inverted.
double repose_angle_degrees(double friction) {
  return std::asin(3.0 * friction / (2.0 * std::numbers::sqrt2 + friction)) * 180.0 / std::numbers::pi;
}

void expect_pile_at_repose_angle(double friction) {
  const test::ScratchDirectory folder("dem");
  const ReposeCalibration table = shipped_repose_calibration();
  const double theta = repose_angle_degrees(friction);
  ColumnSpec spec;
  spec.contact.sliding_friction = table.sliding_friction;
  spec.contact.rolling_friction = rolling_friction_for_repose_angle(table, theta);
  spec.drag_time = 0.25 * std::sqrt(spec.height / spec.gravity);
  spec.seed = 2;  // the calibration's piles are seed 1
  const Deposit deposit = collapse_column(spec, folder.path());
  std::printf("f = %.2f: theta %.2f deg, mu_s %.2f, mu_r %.4f: pile %.2f deg over %d columns (%zu grains)\n",
              friction, theta, spec.contact.sliding_friction, spec.contact.rolling_friction,
              deposit.flank.angle_degrees, deposit.flank.columns, deposit.grains.size());
  EXPECT_GE(deposit.flank.columns, 5);
  EXPECT_NEAR(deposit.flank.angle_degrees, theta, 3.0);
}

TEST(DemRepose, QuasiStaticPileStandsAtThetaOfFrictionPointFiftyFive) {
  expect_pile_at_repose_angle(0.55);
}
TEST(DemRepose, QuasiStaticPileStandsAtThetaOfFrictionPointSeven) {
  expect_pile_at_repose_angle(0.7);
}

}  // namespace
}  // namespace craterkit::dem
