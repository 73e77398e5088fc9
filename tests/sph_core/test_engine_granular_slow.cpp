// Granular flow, long runs (label slow; docs/validation.md, "Granular flow"): the tilted layer at f = 0.7
// and the run-out at a = 1.5 (their f = 0.4 and a = 1 companions run in CI, test_engine_granular.cpp), the
// flank of the deposit left by a collapsed column against the angle of repose, and the run-out at a = 0.5.
// Set-ups in granular_setup.hpp, runs and measurements in granular_checks.hpp; material and parameters as
// in test_engine_granular.cpp.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <string>

#include "sph_core/granular_checks.hpp"

namespace {

using namespace granular_test;

TEST(GranularRepose, TiltedLayerFrictionPointSeven) {
  check_critical_slope(0.7);
}

// Run for 15 sqrt(H/g): with the corrected stress divergence the deposit is still settling at 10 (rms speed
// 0.015 sqrt(gH), over the 0.01 of "at rest"; 0.0014 at 15, run-out unchanged at 1.833).
TEST(GranularCollapse, RunoutAspectRatioOneAndHalf) {
  EXPECT_NEAR(runout_ratio(18, 12, 15.0, "collapse_a150.csv") / (1.2 * 1.5), 1.0, 0.2);
}

// A column of aspect ratio a = H0/L0 = 0.5 (16 x 32 cells) against the back wall, released from the
// lithostatic state, run for 10 sqrt(H0/g) (at rest after ~7.5). The flank slope is the least-squares
// line through the surface profile between 20 % and 80 % of the deposit height on the falling side (the
// undisturbed flat top and the rounded toe left out). Its run-out (L - L0)/L0 is compared with the
// 1.2 a of Lube et al. (2005) as in test_engine_granular.cpp.
struct CollapseResult {
  SlopeFit flank;
  double runout_ratio;
};

CollapseResult collapse(double friction, const std::string& csv) {
  const auto start = std::chrono::steady_clock::now();
  BlockSetup s;
  s.friction = friction;
  s.height_cells = 16;
  s.width_cells = 32;
  s.floor_cells = 72;
  const SimulationConfig config = block_config(s);
  Simulation sim(config, make_block(s, config));
  const double end_time = 10.0 * free_fall_time(s);
  while (sim.time() < end_time) sim.step(end_time);
  const SurfaceProfile profile = surface_profile(sim.particles(), s);
  CollapseResult r{flank_slope(profile, 0.2, 0.8),
                   (runout(profile, s.spacing) - block_width(s)) / block_width(s)};
  const double unit = std::sqrt(s.gravity * block_height(s));
  std::printf(
      "collapse a = 0.5, f = %.2f: flank %.2f deg over %d columns; theta(f) %.2f deg, atan(f) %.2f deg; "
      "(L - L0)/L0 = %.3f (1.2 a = 0.6); end speed %.4f sqrt(gH); %llu steps, %.1f s\n",
      friction, r.flank.angle_degrees, r.flank.columns, repose_angle_degrees(friction),
      std::atan(friction) * degrees, r.runout_ratio, max_speed(sim.particles()) / unit,
      static_cast<unsigned long long>(sim.step_count()),
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  if (const char* dir = std::getenv("CRATERKIT_VALIDATION_OUTPUT")) {
    std::ofstream out(std::string(dir) + "/" + csv);
    out << "# collapse a=0.5 f=" << friction << " flank_deg=" << r.flank.angle_degrees
        << " fit_x=" << r.flank.x_begin << ".." << r.flank.x_end << "\n# x_m,surface_height_m\n";
    for (std::size_t c = 0; c < profile.x.size(); ++c)
      out << profile.x[c] << "," << profile.height[c] << "\n";
  }
  EXPECT_LT(max_speed(sim.particles()), 0.05 * unit);  // at rest
  return r;
}

// Documented in docs/validation.md: the deposit of a collapse is shallower than the angle the same
// material holds when tilted (GranularRepose.TiltedLayer*), by more than the 3 degrees the issue allows.
TEST(GranularCollapseSlow, DepositFlankFrictionPointFour) {
  const CollapseResult r = collapse(0.4, "deposit_f040.csv");
  EXPECT_NEAR(r.flank.angle_degrees, repose_angle_degrees(0.4), 3.0);
  EXPECT_NEAR(r.runout_ratio / 0.6, 1.0, 0.2);
}

TEST(GranularCollapseSlow, DepositFlankFrictionPointSeven) {
  const CollapseResult r = collapse(0.7, "deposit_f070.csv");
  EXPECT_NEAR(r.flank.angle_degrees, repose_angle_degrees(0.7), 3.0);
  EXPECT_NEAR(r.runout_ratio / 0.6, 1.0, 0.2);
}

}  // namespace
