// Granular flow, long runs (label slow; docs/validation.md, "Granular flow"): the tilted layers at f = 0.4
// and 0.7, the run-outs at a = 0.5, 1 and 1.5 (each 4-10 minutes on one core, too long for CI; the
// vertical cut runs in CI, test_engine_granular.cpp), the flank of the pile left by a column collapsed
// freely and quasi-statically against the angle of repose, and the run-out at a = 0.5.
// Set-ups in granular_setup.hpp, runs and measurements in granular_checks.hpp; material and parameters as
// in test_engine_granular.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

#include "sph_core/granular_checks.hpp"

namespace {

using namespace granular_test;

// (a) Angle of repose by tilting (granular_checks.hpp).
TEST(GranularRepose, TiltedLayerFrictionPointFour) {
  check_critical_slope(0.4);
}

TEST(GranularRepose, TiltedLayerFrictionPointSeven) {
  check_critical_slope(0.7);
}

// (b) Run-out (granular_checks.hpp), f = 0.55. a = 1: at rest after 8 sqrt(H/g).
TEST(GranularCollapse, RunoutAspectRatioOne) {
  EXPECT_NEAR(runout_ratio(16, 16, 8.0, "collapse_a100.csv") / 1.2, 1.0, 0.2);
}

// a = 0.5 (16 x 32 cells, the column of the deposit tests below, on their 72-cell floor: the deposit reaches
// 50 cells), f = 0.55 like a = 1 and 1.5: at rest after 10 sqrt(H/g).
TEST(GranularCollapse, RunoutAspectRatioHalf) {
  EXPECT_NEAR(runout_ratio(16, 32, 10.0, "collapse_a050.csv", 72) / (1.2 * 0.5), 1.0, 0.2);
}

// Run for 15 sqrt(H/g): with the corrected stress divergence the deposit is still settling at 10 (rms speed
// 0.015 sqrt(gH), over the 0.01 of "at rest"; 0.0014 at 15, run-out unchanged at 1.833).
TEST(GranularCollapse, RunoutAspectRatioOneAndHalf) {
  EXPECT_NEAR(runout_ratio(18, 12, 15.0, "collapse_a150.csv") / (1.2 * 1.5), 1.0, 0.2);
}

// A column of aspect ratio a = H0/L0 = 0.5 (16 x 32 cells) against the back wall, released from the
// lithostatic state. The flank slope is the least-squares line through the surface profile between 20 % and
// 80 % of the deposit height on the falling side (the undisturbed flat top and the rounded toe left out).
// Resolution studies may set the height in cells with CRATERKIT_PILE_HEIGHT_CELLS (the width and floor
// follow; the spacing stays 5 mm, so the column grows).
BlockSetup half_column(double friction) {
  int height = 16;
  if (const char* cells = std::getenv("CRATERKIT_PILE_HEIGHT_CELLS")) height = std::atoi(cells);
  if (height < 4) ADD_FAILURE() << "CRATERKIT_PILE_HEIGHT_CELLS = " << height << ": needs 4 or more";
  BlockSetup s;
  s.friction = friction;
  s.height_cells = std::max(height, 4);
  s.width_cells = 2 * s.height_cells;
  s.floor_cells = (9 * s.height_cells) / 2;
  return s;
}

struct CollapseResult {
  FlankFit flank;
  double runout_ratio;  // (L - L0)/L0
};

CollapseResult collapse(double friction, double end_units, double drag_units, const std::string& csv) {
  const BlockSetup s = half_column(friction);
  const Deposit d = run_block(s, end_units, drag_units);
  const CollapseResult r{flank_slope(d.profile, 0.2, 0.8),
                         (runout(d.profile, s.spacing) - block_width(s)) / block_width(s)};
  const double unit = std::sqrt(s.gravity * block_height(s));
  std::printf(
      "collapse a = 0.5, f = %.2f, drag time %g sqrt(H/g): flank %.2f deg over %d columns; theta(f) %.2f "
      "deg, "
      "atan(f) %.2f deg; (L - L0)/L0 = %.3f (1.2 a = 0.6); end speed max %.4f, rms %.5f sqrt(gH); %llu "
      "steps, "
      "%.1f s\n",
      friction, drag_units, r.flank.angle_degrees, r.flank.columns, repose_angle_degrees(friction),
      std::atan(friction) * degrees, r.runout_ratio, d.end_speed / unit, d.end_rms_speed / unit,
      static_cast<unsigned long long>(d.steps), d.wall_seconds);
  write_profile(d, csv,
                "collapse a=0.5 f=" + std::to_string(friction) + " drag=" + std::to_string(drag_units) +
                    " flank_deg=" + std::to_string(r.flank.angle_degrees));
  EXPECT_LT(d.end_rms_speed, 0.01 * unit);  // at rest
  return r;
}

// (a) Angle of repose of a collapsed pile. Collapsed freely (10 sqrt(H0/g), at rest after ~7.5), the
// deposit stops far below the angle the material holds (docs/validation.md): the wedge slides out with
// momentum. Documented failures, kept as tests.
TEST(GranularCollapseSlow, DepositFlankFrictionPointFour) {
  const CollapseResult r = collapse(0.4, 10.0, std::numeric_limits<double>::infinity(), "deposit_f040.csv");
  EXPECT_NEAR(r.flank.angle_degrees, repose_angle_degrees(0.4), 3.0);
  EXPECT_NEAR(r.runout_ratio / 0.6, 1.0, 0.2);
}

TEST(GranularCollapseSlow, DepositFlankFrictionPointSeven) {
  const CollapseResult r = collapse(0.7, 10.0, std::numeric_limits<double>::infinity(), "deposit_f070.csv");
  EXPECT_NEAR(r.flank.angle_degrees, repose_angle_degrees(0.7), 3.0);
  EXPECT_NEAR(r.runout_ratio / 0.6, 1.0, 0.2);
}

// The same column collapsed quasi-statically: a drag towards rest with the relaxation time
// 0.25 sqrt(H0/g) (granular_checks.hpp, run_block) takes the inertia out of the collapse, as pouring a pile
// slowly does, so the flank creeps down until it holds itself and stops there: the angle of repose of the
// pile. Run for 25 sqrt(H0/g): f = 0.4 creeps longest (its flank was 24.8 degrees at 15, 23.4-23.5 at 20
// and 25). A stronger drag, 0.1 sqrt(H0/g), ends at the same angle for f = 0.7 (33.1 against 33.2 degrees,
// at 40 sqrt(H0/g)) and creeps more slowly for f = 0.4 (24.6 at 40, still falling): docs/validation.md,
// "(a) Angle of repose". f = 0.7 ends 3.3 degrees below theta(f), a documented failure.
constexpr double quasi_static_drag = 0.25;
constexpr double quasi_static_end = 25.0;

TEST(GranularRepose, QuasiStaticCollapseFrictionPointFour) {
  const CollapseResult r = collapse(0.4, quasi_static_end, quasi_static_drag, "pile_f040.csv");
  EXPECT_NEAR(r.flank.angle_degrees, repose_angle_degrees(0.4), 3.0);
}

TEST(GranularRepose, QuasiStaticCollapseFrictionPointFiftyFive) {
  const CollapseResult r = collapse(0.55, quasi_static_end, quasi_static_drag, "pile_f055.csv");
  EXPECT_NEAR(r.flank.angle_degrees, repose_angle_degrees(0.55), 3.0);
}

TEST(GranularRepose, QuasiStaticCollapseFrictionPointSeven) {
  const CollapseResult r = collapse(0.7, quasi_static_end, quasi_static_drag, "pile_f070.csv");
  EXPECT_NEAR(r.flank.angle_degrees, repose_angle_degrees(0.7), 3.0);
}

}  // namespace
