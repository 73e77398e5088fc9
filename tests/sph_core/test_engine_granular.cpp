// Granular flow under gravity (issue 5): quasi-2D column collapses of a cohesionless Lundborg material
// (angle of repose, run-out scaling) and a vertical cut in a cohesive one, on an elastic floor backed by
// fixed particles (granular_setup.hpp). The material is the late-stage medium of physics.md section 3: the
// linear low-sound-speed law with a bulk sound speed of 10 sqrt(g H) (so the flow stays below Mach ~0.15 and
// the static compression rho g H / A is 1 %), Poisson's ratio 0.3, rho0 = 1500 kg/m^3, g = 9.81 m/s^2.
// Only the friction and the cohesion matter for the comparisons; the soft, slow medium keeps the runs
// at a few thousand steps. Docs: docs/validation.md, "Granular flow".
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "sph_core/granular_setup.hpp"

namespace {

using namespace granular_test;

constexpr double degrees = 180.0 / std::numbers::pi;

// Angle of repose from the friction coefficient, inverting f = 2 sqrt(2) sin(theta) / (3 - sin(theta))
// (Luther et al. 2022; physics.md section 2): sin(theta) = 3 f / (2 sqrt(2) + f).
double repose_angle_degrees(double friction) {
  return std::asin(3.0 * friction / (2.0 * std::sqrt(2.0) + friction)) * degrees;
}

struct Deposit {
  SurfaceProfile profile;
  double end_speed;      // largest particle speed at the end, m/s
  double end_rms_speed;  // rms speed of the granular particles at the end, m/s
  double wall_seconds;
  std::size_t particles;
  std::uint64_t steps;
};

void write_profile(const Deposit& d, const std::string& name, const std::string& comment) {
  const char* dir = std::getenv("CRATERKIT_VALIDATION_OUTPUT");
  if (dir == nullptr) return;
  std::ofstream out(std::string(dir) + "/" + name);
  out << "# " << comment << "\n# x_m,surface_height_m\n";
  for (std::size_t c = 0; c < d.profile.x.size(); ++c)
    out << d.profile.x[c] << "," << d.profile.height[c] << "\n";
}

// Runs the block for end_time_units free-fall times sqrt(H/g).
Deposit run_block(const BlockSetup& s, double end_time_units) {
  const auto start = std::chrono::steady_clock::now();
  const SimulationConfig config = block_config(s);
  Simulation sim(config, make_block(s, config));
  const double end_time = end_time_units * free_fall_time(s);
  const bool verbose = std::getenv("GRANULAR_VERBOSE") != nullptr;
  double next_report = 0.0;
  while (sim.time() < end_time) {
    sim.step(end_time);
    if (verbose && sim.time() >= next_report) {
      const auto profile = surface_profile(sim.particles(), s);
      std::printf("  t %.3f (%.2f t_ff) step %llu dt %.2e max v %.3f m/s run-out %.4f m\n", sim.time(),
                  sim.time() / free_fall_time(s), static_cast<unsigned long long>(sim.step_count()),
                  sim.next_time_step(), max_speed(sim.particles()), runout(profile, s.spacing));
      next_report += 0.5 * free_fall_time(s);
    }
  }
  Deposit d;
  d.profile = surface_profile(sim.particles(), s);
  d.end_speed = max_speed(sim.particles());
  d.end_rms_speed = rms_speed(sim.particles());
  d.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  d.particles = sim.particles().size();
  d.steps = sim.step_count();
  return d;
}

// ---------------------------------------------------------------------------------------------------
// (a) Angle of repose, static part: the steepest slope a cohesionless layer holds, found by tilting.
// An infinite slope (granular_setup.hpp, SlopeSetup: 12 cells deep on an elastic floor, periodic along
// the slope) starts in its static elastic state at theta(f) - 8 degrees and settles for 8 sqrt(D/g);
// then gravity is tilted by 0.5 degrees at a time (the run continues from its particles, as a restart
// does, under the new gravity), each tilt held for 2 sqrt(D/g), until the layer flows: its mean
// downslope speed, averaged over the second half of the hold, exceeds 0.005 sqrt(g D). The critical
// angle is the midpoint of the last standing and the first flowing tilt.
// Why tilting rather than starting each angle from the continuum state: that state is not the discrete
// equilibrium, and the elastic ringing it starts (about 0.06 sqrt(gD) at the surface of a 24-cell layer)
// overshoots the yield stress of a slope close to critical, so the layer failed degrees too early.
// Continuum expectation for this yield rule: sqrt(J2) = |S_xz| = rho g d sin(beta) against
// Y = f P = f rho g d cos(beta), so the slope fails at tan(beta) = f; atan(f) lies within 1.6 degrees of
// the theta(f) for 0.4 <= f <= 0.7 (docs/validation.md).
struct Tilt {
  double critical_degrees;
  std::vector<double> angles, speeds;  // end-of-tilt mean downslope speed / sqrt(g D)
};

Tilt tilt_until_flow(double friction, int depth_cells) {
  SlopeSetup s;
  s.friction = friction;
  s.depth_cells = depth_cells;
  s.slope_degrees = std::round(2.0 * (repose_angle_degrees(friction) - 8.0)) / 2.0;
  const double hold = 2.0 * std::sqrt(layer_depth(s) / s.gravity);
  const double unit = std::sqrt(s.gravity * layer_depth(s));
  SimulationConfig config = slope_config(s);
  auto sim = std::make_unique<Simulation>(config, make_slope(s, config));
  Tilt tilt{NAN, {}, {}};
  // Settle: the continuum state rings the layer for a few sqrt(D/g) (see above); 8 degrees below
  // theta(f) the ringing cannot reach the yield stress.
  while (sim->time() < 4.0 * hold) sim->step(4.0 * hold);
  while (s.slope_degrees < repose_angle_degrees(friction) + 8.0) {
    // Mean downslope speed over the second half of the hold, sampled 20 times: the elastic ringing
    // after a tilt (up to ~0.008 sqrt(g D) at the end of a hold) averages out, a flow does not.
    const double start = sim->time();
    while (sim->time() < start + 0.5 * hold) sim->step(start + 0.5 * hold);
    double v = 0.0;
    for (int k = 1; k <= 20; ++k) {
      const double t = start + 0.5 * hold * (1.0 + k / 20.0);
      while (sim->time() < t) sim->step(t);
      v += mean_downslope_velocity(sim->particles()) / unit / 20.0;
    }
    tilt.angles.push_back(s.slope_degrees);
    tilt.speeds.push_back(v);
    if (v > 0.005) {
      tilt.critical_degrees = s.slope_degrees - 0.25;
      break;
    }
    s.slope_degrees += 0.5;
    config = slope_config(s);
    auto next =
        std::make_unique<Simulation>(config, make_slope(s, config), sim->particles(), sim->attributes());
    sim = std::move(next);
  }
  return tilt;
}

void check_critical_slope(double friction) {
  const auto start = std::chrono::steady_clock::now();
  const Tilt tilt = tilt_until_flow(friction, 12);
  std::printf(
      "tilted layer f = %.2f: critical %.2f deg; theta(f) = %.2f deg (Luther et al. 2022), atan(f) = %.2f "
      "deg; %.1f s\n",
      friction, tilt.critical_degrees, repose_angle_degrees(friction), std::atan(friction) * degrees,
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  for (std::size_t k = 0; k < tilt.angles.size(); ++k)
    std::printf("  %.2f deg: %.5f\n", tilt.angles[k], tilt.speeds[k]);
  if (const char* dir = std::getenv("CRATERKIT_VALIDATION_OUTPUT")) {
    char name[64];
    std::snprintf(name, sizeof name, "/tilt_f%03d.csv", static_cast<int>(std::lround(100.0 * friction)));
    std::ofstream out(std::string(dir) + name);
    out << "# tilted layer f=" << friction << " critical_deg=" << tilt.critical_degrees
        << "\n# slope_deg,mean_speed_over_sqrt_gD\n";
    for (std::size_t k = 0; k < tilt.angles.size(); ++k)
      out << tilt.angles[k] << "," << tilt.speeds[k] << "\n";
  }
  EXPECT_NEAR(tilt.critical_degrees, repose_angle_degrees(friction), 3.0);
}

TEST(GranularRepose, TiltedLayerFrictionPointFour) {
  check_critical_slope(0.4);
}
TEST(GranularRepose, TiltedLayerFrictionPointSeven) {
  check_critical_slope(0.7);
}

// ---------------------------------------------------------------------------------------------------
// (b) Column collapse run-out against the quasi-2D experiments of Lube et al. (2005, Phys. Rev. E 72,
// 041301): (L_inf - L0)/L0 = 1.2 a for a = H0/L0 < 1.8 (Lajeunesse et al. 2005, Phys. Fluids 17, 103302,
// also find run-out linear in a at small a in their channel). A column against the back wall, released
// at t = 0 from the lithostatic state, f = 0.55 (theta = 29 degrees, a sand); run-out = far edge of the
// last column of the surface profile holding at least half a layer of particles, measured at rest
// (rms speed of the grains below 0.01 sqrt(g H0): 8 sqrt(H0/g) for a = 1, 10 for a = 1.5). Accepted:
// within 20 % of 1.2 a, our reading of the spread of the experimental points about the fit (the papers
// themselves were not at hand here; the coefficient 1.2 and the bound 1.8 are as quoted in issue 5).
double runout_ratio(int height_cells, int width_cells, double end_units, const std::string& csv) {
  BlockSetup s;
  s.friction = 0.55;
  s.height_cells = height_cells;
  s.width_cells = width_cells;
  s.floor_cells = 48;
  const Deposit d = run_block(s, end_units);
  const double a = static_cast<double>(height_cells) / width_cells;
  const double L0 = block_width(s);
  const double ratio = (runout(d.profile, s.spacing) - L0) / L0;
  std::printf(
      "collapse a = %.2f: (L - L0)/L0 = %.3f, Lube 1.2 a = %.3f (%+.1f %%); end speed max %.4f, rms %.5f sqrt(gH); %zu "
      "particles, %llu steps, %.1f s\n",
      a, ratio, 1.2 * a, 100.0 * (ratio / (1.2 * a) - 1.0),
      d.end_speed / std::sqrt(s.gravity * block_height(s)),
      d.end_rms_speed / std::sqrt(s.gravity * block_height(s)), d.particles,
      static_cast<unsigned long long>(d.steps), d.wall_seconds);
  write_profile(d, csv, "collapse a=" + std::to_string(a) + " ratio=" + std::to_string(ratio));
  EXPECT_LT(d.end_rms_speed, 0.01 * std::sqrt(s.gravity * block_height(s)));  // at rest
  return ratio;
}

TEST(GranularCollapse, RunoutAspectRatioOne) {
  EXPECT_NEAR(runout_ratio(16, 16, 8.0, "collapse_a100.csv") / 1.2, 1.0, 0.2);
}

TEST(GranularCollapse, RunoutAspectRatioOneAndHalf) {
  EXPECT_NEAR(runout_ratio(18, 12, 10.0, "collapse_a150.csv") / (1.2 * 1.5), 1.0, 0.2);
}

// ---------------------------------------------------------------------------------------------------
// (c) Vertical cut in a cohesive material. A block 24 cells wide and H = 16 cells high against the back
// wall starts in the elastic state of a free-standing face (sigma_xx = 0; granular_setup.hpp) with
// f = 0.55; its cohesion Y0 sets the Rankine critical height H_c = 4 c/(rho g) tan(45 deg + phi/2).
// Which (c, phi) belong to (Y0, f): this yield rule compares sqrt(J2) with Y0 + f P, a Drucker-Prager cone.
// In plane strain with plastic flow along S (radial return, no plastic volume change) the out-of-plane
// deviator vanishes at yield, sqrt(J2) = (sigma1 - sigma3)/2 and P = (sigma1 + sigma3)/2, so the cone is
// exactly Mohr-Coulomb with sin(phi) = f, c cos(phi) = Y0: H_c = 8.89 Y0/(rho g) for f = 0.55. Matching
// the cone to Mohr-Coulomb on the compression meridian instead (the 3D match, f = 2 sqrt(3) sin(phi) /
// (3 - sin(phi))) gives H_c = 5.08 Y0/(rho g). The cut must stand at half the lower value and fail at
// twice the higher one. At H = 0.5 x 5.08 Y0/(rho g) the whole block is elastic (sqrt(J2) < Y
// everywhere in the initial state, the largest ratio 0.81 at the toe); at 2 x 8.89 Y0/(rho g) it yields
// from the toe up at once.
// Measured: the mean displacement of the top front corner (2 x 2 cells x all y) after 5 sqrt(H/g).
// Rankine height 4 c/(rho g) tan(45 deg + phi/2) in units of Y0/(rho g), for the two matches above.
double rankine_height_plane_strain(double f) {
  const double phi = std::asin(f), c = 1.0 / std::cos(phi);
  return 4.0 * c * std::tan(0.25 * std::numbers::pi + 0.5 * phi);
}
double rankine_height_compression_meridian(double f) {
  const double s = 3.0 * f / (2.0 * std::sqrt(3.0) + f), phi = std::asin(s);
  const double c = std::sqrt(3.0) * (3.0 - s) / (6.0 * std::cos(phi));  // Y0 = 6 c cos(phi)/(sqrt(3)(3 - s))
  return 4.0 * c * std::tan(0.25 * std::numbers::pi + 0.5 * phi);
}

double cut_corner_displacement(double height_over_critical_unit) {
  BlockSetup s;
  s.friction = 0.55;
  s.height_cells = 16;
  s.width_cells = 24;
  s.floor_cells = 48;
  s.initial = InitialStress::free_standing;
  s.cohesion = s.density * s.gravity * block_height(s) / height_over_critical_unit;
  const SimulationConfig config = block_config(s);
  ProblemSetup problem = make_block(s, config);
  // The top front corner: moving particles within 2 cells of the face and of the top.
  std::vector<std::uint64_t> corner;
  const auto& p0 = problem.particles;
  for (std::size_t k = 0; k < p0.size(); ++k) {
    if ((p0.flags[k] & particle_fixed) == 0 && p0.x[k] > block_width(s) - 2.0 * s.spacing &&
        p0.z[k] > block_height(s) - 2.0 * s.spacing)
      corner.push_back(p0.id[k]);
  }
  std::vector<double> x0(p0.size()), z0(p0.size());
  for (std::size_t k = 0; k < p0.size(); ++k) {
    x0[p0.id[k]] = p0.x[k];
    z0[p0.id[k]] = p0.z[k];
  }
  Simulation sim(config, std::move(problem));
  const double end_time = 5.0 * free_fall_time(s);
  while (sim.time() < end_time) sim.step(end_time);
  std::vector<bool> in_corner(x0.size(), false);
  for (auto id : corner) in_corner[id] = true;
  const auto& p = sim.particles();
  double sum = 0.0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (!in_corner[p.id[k]]) continue;
    sum += std::hypot(p.x[k] - x0[p.id[k]], p.z[k] - z0[p.id[k]]);
  }
  const double displacement = sum / corner.size() / block_height(s);
  std::printf("vertical cut H = %.2f Y0/(rho g): corner displacement %.4f H after 5 sqrt(H/g), %llu steps\n",
              height_over_critical_unit, displacement, static_cast<unsigned long long>(sim.step_count()));
  if (const char* dir = std::getenv("CRATERKIT_VALIDATION_OUTPUT")) {
    const SurfaceProfile profile = surface_profile(p, s);
    std::ofstream out(std::string(dir) +
                      (height_over_critical_unit < 5.0 ? "/cut_stands.csv" : "/cut_fails.csv"));
    out << "# vertical cut H=" << height_over_critical_unit << " Y0/(rho g), corner displacement "
        << displacement << " H\n# x_m,surface_height_m\n";
    for (std::size_t c = 0; c < profile.x.size(); ++c)
      out << profile.x[c] << "," << profile.height[c] << "\n";
  }
  return displacement;
}

TEST(GranularCut, StandsBelowTheRankineHeight) {
  EXPECT_LT(cut_corner_displacement(0.5 * rankine_height_compression_meridian(0.55)), 0.02);
}

TEST(GranularCut, FailsAboveTheRankineHeight) {
  EXPECT_GT(cut_corner_displacement(2.0 * rankine_height_plane_strain(0.55)), 0.2);
}

}  // namespace
