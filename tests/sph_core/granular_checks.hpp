#pragma once
// Granular-flow checks shared by the physics and slow tests (test_engine_granular.cpp,
// test_engine_granular_slow.cpp): the runs and measurements of the granular validation; the set-ups
// are in granular_setup.hpp. Docs: docs/validation.md, "Granular flow".
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "craterkit/sph/physics/yield_strength.hpp"
#include "sph_core/granular_setup.hpp"

namespace granular_test {

inline constexpr double degrees = 180.0 / std::numbers::pi;

// Angle of repose from the friction coefficient (Luther et al. 2022; docs/physics.md section 2).
inline double repose_angle_degrees(double friction) {
  return craterkit::sph::repose_angle_from_friction(friction) * degrees;
}

struct Deposit {
  SurfaceProfile profile;
  double end_speed;      // largest particle speed at the end, m/s
  double end_rms_speed;  // rms speed of the granular particles at the end, m/s
  double wall_seconds;
  std::size_t particles;
  std::uint64_t steps;
};

inline void write_profile(const Deposit& d, const std::string& name, const std::string& comment) {
  const char* dir = std::getenv("CRATERKIT_VALIDATION_OUTPUT");
  if (dir == nullptr) return;
  std::ofstream out(std::string(dir) + "/" + name);
  out << "# " << comment << "\n# x_m,surface_height_m\n";
  for (std::size_t c = 0; c < d.profile.x.size(); ++c)
    out << d.profile.x[c] << "," << d.profile.height[c] << "\n";
}

// Runs the block for end_time_units free-fall times sqrt(H/g). With a finite drag_time_units the velocity of
// every moving particle is multiplied by exp(-dt / tau) after each step, tau = drag_time_units sqrt(H/g): a
// drag towards rest, applied between steps like an external force (the stored accelerations are those of
// the undamped forces; the next step starts from the damped velocities). It takes the inertia out of a
// collapse without changing what is in equilibrium (the quasi-static collapse of GranularRepose).
inline Deposit run_block(const BlockSetup& s, double end_time_units,
                         double drag_time_units = std::numeric_limits<double>::infinity()) {
  const auto start = std::chrono::steady_clock::now();
  const StandardProblemConfig config = block_config(s);
  Simulation sim(config.simulation.solver, make_block(s, config));
  const double end_time = end_time_units * free_fall_time(s);
  const bool verbose = std::getenv("GRANULAR_VERBOSE") != nullptr;
  double next_report = 0.0;
  const double drag_time = drag_time_units * free_fall_time(s);
  while (sim.time() < end_time) {
    const double start_of_step = sim.time();
    sim.step(end_time);
    if (std::isfinite(drag_time)) {
      const double factor = std::exp(-(sim.time() - start_of_step) / drag_time);
      Particles& p = sim.particles();
      for (std::size_t k = 0; k < p.size(); ++k) {
        p.vx[k] *= factor;
        p.vy[k] *= factor;
        p.vz[k] *= factor;
      }
    }
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

inline Tilt tilt_until_flow(double friction, int depth_cells) {
  SlopeSetup s;
  s.friction = friction;
  s.depth_cells = depth_cells;
  s.slope_degrees = std::round(2.0 * (repose_angle_degrees(friction) - 8.0)) / 2.0;
  const double hold = 2.0 * std::sqrt(layer_depth(s) / s.gravity);
  const double unit = std::sqrt(s.gravity * layer_depth(s));
  StandardProblemConfig config = slope_config(s);
  auto sim = std::make_unique<Simulation>(config.simulation.solver, make_slope(s, config));
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
    auto next = std::make_unique<Simulation>(config.simulation.solver, make_slope(s, config),
                                             sim->particles(), sim->state());
    sim = std::move(next);
  }
  return tilt;
}

inline void check_critical_slope(double friction) {
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

}  // namespace granular_test
