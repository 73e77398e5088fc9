// Granular flow, long runs (label slow; docs/validation.md, "Granular flow"): the tilted layers at f = 0.4
// and 0.7, the run-out at a = 1.5, the flank and run-out of the deposit of a column collapsed freely
// (a = 0.5: f = 0.4, 0.55, 0.7; a = 1: f = 0.55) and the flank of the pile of one collapsed quasi-statically
// (f = 0.4, 0.55, 0.7), against the angle of repose and Lube et al.'s run-out (each 4-12 minutes on one core,
// too long for CI; the vertical cut runs in CI, test_engine_granular.cpp).
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

// A column of aspect ratio a = H0/L0 = 0.5 (height_cells x 2 height_cells, 5 mm cells) against the back wall,
// released from the lithostatic state. The flank slope is the least-squares line through the surface profile
// between 20 % and 80 % of the deposit height on the falling side (the undisturbed flat top and the rounded
// toe left out). Resolution studies may set the height in cells with CRATERKIT_PILE_HEIGHT_CELLS (the width
// and floor follow; the spacing stays 5 mm, so the column grows).
BlockSetup half_column(double friction, int height_cells) {
  int height = height_cells;
  if (const char* cells = std::getenv("CRATERKIT_PILE_HEIGHT_CELLS")) height = std::atoi(cells);
  if (height < 4) ADD_FAILURE() << "CRATERKIT_PILE_HEIGHT_CELLS = " << height << ": needs 4 or more";
  BlockSetup s;
  s.friction = friction;
  s.height_cells = std::max(height, 4);
  s.width_cells = 2 * s.height_cells;
  s.floor_cells = (9 * s.height_cells) / 2;
  return s;
}

// The freely collapsed column: 16 cells high (at 24 its f = 0.55 deposit has the same flank, 22.16 against
// 22.05 degrees).
constexpr int deposit_height_cells = 16;

// The column of a = 1 (16 x 16 cells on a 48-cell floor, as the run-out at a = 1 always had).
BlockSetup square_column(double friction) {
  BlockSetup s;
  s.friction = friction;
  s.height_cells = 16;
  s.width_cells = 16;
  s.floor_cells = 48;
  return s;
}

struct CollapseResult {
  FlankFit flank;
  double runout_ratio;  // (L - L0)/L0
};

CollapseResult collapse(const BlockSetup& s, double end_units, double drag_units, const std::string& csv) {
  const double friction = s.friction;
  const double a = block_height(s) / block_width(s);
  const Deposit d = run_block(s, end_units, drag_units);
  const CollapseResult r{flank_slope(d.profile, 0.2, 0.8),
                         (runout(d.profile, s.spacing) - block_width(s)) / block_width(s)};
  const double unit = std::sqrt(s.gravity * block_height(s));
  std::printf(
      "collapse a = %.2f, f = %.2f, drag time %g sqrt(H/g): flank %.2f deg over %d columns; theta(f) %.2f "
      "deg, atan(f) %.2f deg; (L - L0)/L0 = %.3f (1.2 a = %.3f); end speed max %.4f, rms %.5f sqrt(gH); %llu "
      "steps, %.1f s\n",
      a, friction, drag_units, r.flank.angle_degrees, r.flank.columns, repose_angle_degrees(friction),
      std::atan(friction) * degrees, r.runout_ratio, 1.2 * a, d.end_speed / unit, d.end_rms_speed / unit,
      static_cast<unsigned long long>(d.steps), d.wall_seconds);
  write_profile(d, csv,
                "collapse a=" + std::to_string(a) + " f=" + std::to_string(friction) + " drag=" +
                    std::to_string(drag_units) + " flank_deg=" + std::to_string(r.flank.angle_degrees));
  EXPECT_LT(d.end_rms_speed, 0.01 * unit);  // at rest
  return r;
}

// (a) Angle of repose of a collapsed pile, and (b) its run-out. Collapsed freely (10 sqrt(H0/g), at rest
// after ~7.5), the deposit stops far below the angle the material holds (docs/validation.md): the wedge
// slides out with momentum. The flanks are documented failures, kept as tests; so are the run-outs at
// f = 0.4 and 0.7, which fall with the friction (1.2 a holds at f = 0.55).
constexpr double free_collapse = std::numeric_limits<double>::infinity();  // no drag

TEST(GranularCollapseSlow, DepositFlankFrictionPointFour) {
  const CollapseResult r =
      collapse(half_column(0.4, deposit_height_cells), 10.0, free_collapse, "deposit_f040.csv");
  EXPECT_NEAR(r.flank.angle_degrees, repose_angle_degrees(0.4), 3.0);
  EXPECT_NEAR(r.runout_ratio / 0.6, 1.0, 0.2);
}

// f = 0.55, a = 0.5: the column of the run-out at a = 0.5 (16 x 32 cells on a 72-cell floor: the deposit
// reaches 50 cells).
TEST(GranularCollapseSlow, DepositFlankFrictionPointFiftyFive) {
  const CollapseResult r =
      collapse(half_column(0.55, deposit_height_cells), 10.0, free_collapse, "deposit_f055.csv");
  EXPECT_NEAR(r.flank.angle_degrees, repose_angle_degrees(0.55), 3.0);
  EXPECT_NEAR(r.runout_ratio / 0.6, 1.0, 0.2);
}

TEST(GranularCollapseSlow, DepositFlankFrictionPointSeven) {
  const CollapseResult r =
      collapse(half_column(0.7, deposit_height_cells), 10.0, free_collapse, "deposit_f070.csv");
  EXPECT_NEAR(r.flank.angle_degrees, repose_angle_degrees(0.7), 3.0);
  EXPECT_NEAR(r.runout_ratio / 0.6, 1.0, 0.2);
}

// f = 0.55, a = 1 (at rest after 8 sqrt(H/g)).
TEST(GranularCollapseSlow, DepositFlankAspectRatioOne) {
  const CollapseResult r = collapse(square_column(0.55), 8.0, free_collapse, "deposit_a100.csv");
  EXPECT_NEAR(r.flank.angle_degrees, repose_angle_degrees(0.55), 3.0);
  EXPECT_NEAR(r.runout_ratio / 1.2, 1.0, 0.2);
}

// (b) Run-out against the quasi-2D experiments of Lube et al. (2005, Phys. Rev. E 72, 041301):
// (L_inf - L0)/L0 = 1.2 a for a = H0/L0 < 1.8 (Lajeunesse et al. 2005, Phys. Fluids 17, 103302, also find
// run-out linear in a at small a in their channel); run-out = far edge of the last column of the surface
// profile holding at least half a layer of particles (granular_setup.hpp, runout), measured at rest.
// Accepted: within 20 % of 1.2 a, our reading of the spread of the experimental points about the fit (the
// papers themselves were not at hand here; the coefficient 1.2 and the bound 1.8 are as quoted in
// docs/validation.md). a = 0.5 and 1 are the deposit tests above; a = 1.5 (18 x 12 cells on a 48-cell floor,
// f = 0.55) here, run for 15 sqrt(H/g): with the corrected stress divergence the deposit is still settling at
// 10 (rms speed 0.015 sqrt(gH), over the 0.01 of "at rest"; 0.0014 at 15, run-out unchanged at 1.833). Its
// flank is not checked: a column this tall leaves no flat top.
TEST(GranularCollapse, RunoutAspectRatioOneAndHalf) {
  BlockSetup s;
  s.friction = 0.55;
  s.height_cells = 18;
  s.width_cells = 12;
  s.floor_cells = 48;
  const CollapseResult r = collapse(s, 15.0, free_collapse, "collapse_a150.csv");
  EXPECT_NEAR(r.runout_ratio / (1.2 * 1.5), 1.0, 0.2);
}

// The same column collapsed quasi-statically: a drag towards rest with the relaxation time
// 0.25 sqrt(H0/g) (granular_checks.hpp, run_block) takes the inertia out of the collapse, as pouring a pile
// slowly does, so the flank creeps down until it holds itself and stops there: the angle of repose of the
// pile. Run for 25 sqrt(H0/g): f = 0.4 creeps longest (at 16 cells its flank was 24.8 degrees at 15,
// 23.4-23.5 at 20 and 25). A stronger drag, 0.1 sqrt(H0/g), ends at the same angle for f = 0.7 (33.1
// against 33.2 degrees at 16 cells, at 40 sqrt(H0/g)) and creeps more slowly for f = 0.4 (24.6 at 40, still
// falling): docs/validation.md, "(a) Angle of repose". The piles are 24 cells high (12-21 minutes each on
// one core): at 16 cells f = 0.7 ended 3.3 degrees below theta(f), at 24 cells 2.8 (the error falls with the
// spacing; f = 0.4 and 0.55 are within 3 degrees at both).
constexpr int pile_height_cells = 24;
constexpr double quasi_static_drag = 0.25;
constexpr double quasi_static_end = 25.0;

TEST(GranularRepose, QuasiStaticCollapseFrictionPointFour) {
  const CollapseResult r =
      collapse(half_column(0.4, pile_height_cells), quasi_static_end, quasi_static_drag, "pile_f040.csv");
  EXPECT_NEAR(r.flank.angle_degrees, repose_angle_degrees(0.4), 3.0);
}

TEST(GranularRepose, QuasiStaticCollapseFrictionPointFiftyFive) {
  const CollapseResult r =
      collapse(half_column(0.55, pile_height_cells), quasi_static_end, quasi_static_drag, "pile_f055.csv");
  EXPECT_NEAR(r.flank.angle_degrees, repose_angle_degrees(0.55), 3.0);
}

TEST(GranularRepose, QuasiStaticCollapseFrictionPointSeven) {
  const CollapseResult r =
      collapse(half_column(0.7, pile_height_cells), quasi_static_end, quasi_static_drag, "pile_f070.csv");
  EXPECT_NEAR(r.flank.angle_degrees, repose_angle_degrees(0.7), 3.0);
}

}  // namespace
