#pragma once
// Quasi-two-dimensional granular set-ups under gravity for the issue-5 validation (test code, not
// engine): a rectangular block of Lundborg material (x in [0, width), z in [0, height)) on a floor and
// against a back wall, periodic across y (7 lattice cells), under constant gravity (0, 0, -g).
// Measurements on the deposit: the free-surface profile z_s(x), the slope fitted to it, and the run-out.
//
// Walls: three layers of an elastic solid (material 1: same density and moduli as the granular
// material, never yielding) backed by three layers of fixed particles. Why not fixed particles alone:
// they carry no stress (the engine evolves none for them), so the pair force a fixed neighbour j exerts
// holds only sigma_i/rho_i^2. Next to them a stressed particle loses half of its support: the floor acts
// on the bottom layer like a stress-free surface and supplies basal shear only through the kernel
// asymmetry the particle builds by sliding. A cohesionless layer (f = 0.7, 24 cells) started in its
// static state at 33 degrees (atan 0.7 = 35 deg) on a fixed floor slid at its base (bottom layer at
// 0.02 sqrt(g D) after sqrt(D/g)). The elastic
// layer carries stress like the material it supports, so the granular particles see a continuum with a
// no-slip, stress-carrying base; the fixed backing holds the elastic layer, which can take any stress
// the imperfect fixed interface demands without yielding.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include "craterkit/common/flank_slope.hpp"
#include "craterkit/sph/run/standard_problem_config.hpp"
#include "sph_core/solid_test_setups.hpp"

namespace granular_test {

using namespace craterkit::sph;

// How the block starts.
enum class InitialStress {
  lithostatic,   // isotropic P = rho g depth, S = 0: a column whose retaining gate is removed at t = 0
  free_standing  // sigma_zz = -rho g depth, sigma_xx = 0, sigma_yy = nu sigma_zz (plane strain): the
                 // elastic state of a block with traction-free vertical faces (a cut just excavated)
};

struct BlockSetup {
  double spacing = 0.005;            // dx, m
  int width_cells = 20;              // block width along x
  int height_cells = 20;             // block height along z
  int floor_cells = 80;              // floor length along x from x = 0
  int across_cells = 7;              // periodic width along y
  double gravity = 9.81;             // m/s^2
  double density = 1500.0;           // rho0, kg/m^3
  double sound_speed_factor = 10.0;  // bulk c = factor sqrt(g height): Mach <~ 0.15 in the collapse
  double poisson_ratio = 0.3;
  double friction = 0.55;  // f
  double cohesion = 0.0;   // Y0, Pa
  InitialStress initial = InitialStress::lithostatic;
};

inline double block_height(const BlockSetup& s) {
  return s.height_cells * s.spacing;
}
inline double block_width(const BlockSetup& s) {
  return s.width_cells * s.spacing;
}
inline double bulk_modulus(const BlockSetup& s) {
  const double c = s.sound_speed_factor * std::sqrt(s.gravity * block_height(s));
  return s.density * c * c;
}
// Free-fall time scale sqrt(H/g), s.
inline double free_fall_time(const BlockSetup& s) {
  return std::sqrt(block_height(s) / s.gravity);
}

// The wall layers' material: elastic, same density, bulk and shear moduli as the granular material.
inline Material wall_material(double density, double bulk_modulus, double poisson_ratio) {
  Material m = solid_test::granular_material(density, bulk_modulus, poisson_ratio, 0.0, 0.0);
  m.name = "elastic_wall";
  m.strength = VonMisesStrength{1e6 * bulk_modulus};
  return m;
}

inline Material block_material(const BlockSetup& s) {
  return solid_test::granular_material(s.density, bulk_modulus(s), s.poisson_ratio, s.friction, s.cohesion);
}

// Configuration shared by the granular runs: gravity, the Morris-Monaghan viscosity switch (alpha decays
// to 0.1 in shear flow: with alpha = 1 the artificial viscosity ~ alpha c h/10 would make the collapse
// flow at a Reynolds number of ~20), h following the density only (no steering at free surfaces), and
// h capped so that the periodic width holds the interaction range.
inline StandardProblemConfig block_config(const BlockSetup& s) {
  StandardProblemConfig config;
  config.simulation.solver.gravity = {0.0, 0.0, -s.gravity};
  config.simulation.solver.viscosity.viscosity_switch = ViscositySwitch::morris_monaghan;
  config.simulation.solver.smoothing.neighbour_band = 1.0;
  config.simulation.solver.smoothing.max_smoothing_length =
      1.3 * config.simulation.solver.smoothing.eta * s.spacing;
  return config;
}

inline ProblemSetup make_block(const BlockSetup& s, const StandardProblemConfig& config) {
  const double dx = s.spacing, rho0 = s.density, g = s.gravity, H = block_height(s);
  const double K = bulk_modulus(s);
  const double eta = config.simulation.solver.smoothing.eta,
               alpha = config.simulation.solver.viscosity.alpha_min;
  ProblemSetup problem;
  problem.materials = {block_material(s)};
  problem.materials.push_back(wall_material(s.density, K, s.poisson_ratio));
  auto& p = problem.particles;
  const int wall = 6, elastic = 3;  // layers: the inner `elastic` ones are material 1, the rest fixed
  // Initial state under a vertical load rho g (H - z) (the block's and that of the elastic floor under
  // the block; elsewhere the walls start unstressed).
  const auto load = [&](std::size_t k, double z) {
    const double vertical = rho0 * g * (H - z);  // -sigma_zz, Pa
    const double pressure =
        s.initial == InitialStress::free_standing ? vertical * (1.0 + s.poisson_ratio) / 3.0 : vertical;
    p.density[k] = rho0 * (1.0 + pressure / K);
    p.mass[k] = p.density[k] * dx * dx * dx;
    if (s.initial == InitialStress::free_standing) {
      // S = sigma + P I with sigma = diag(0, -nu v, -v), P = (1 + nu) v / 3.
      p.stress_xx[k] = pressure;
      p.stress_yy[k] = pressure - s.poisson_ratio * vertical;
    }
  };
  const auto add_wall = [&](int i, int j, int l) {
    const bool fixed = i < elastic - wall || l < elastic - wall;
    const double z = (l + 0.5) * dx;
    const auto k =
        solid_test::add_particle(p, (i + 0.5) * dx, (j + 0.5) * dx, z, dx, rho0, eta, alpha, fixed);
    if (fixed) return;
    p.material[k] = 1;
    if (i >= 0 && i < s.width_cells && l < 0) load(k, z);
  };
  // Floor below z = 0 from the back of the wall to the end of the floor.
  for (int i = -wall; i < s.floor_cells; ++i)
    for (int j = 0; j < s.across_cells; ++j)
      for (int l = -wall; l < 0; ++l) add_wall(i, j, l);
  // Back wall at x < 0, up to 1.5 times the block height.
  const int wall_height = static_cast<int>(std::ceil(1.5 * s.height_cells));
  for (int i = -wall; i < 0; ++i)
    for (int j = 0; j < s.across_cells; ++j)
      for (int l = 0; l < wall_height; ++l) add_wall(i, j, l);
  // The block, at the density the linear law needs for its initial pressure.
  for (int i = 0; i < s.width_cells; ++i) {
    for (int j = 0; j < s.across_cells; ++j) {
      for (int l = 0; l < s.height_cells; ++l) {
        const double z = (l + 0.5) * dx;
        load(solid_test::add_particle(p, (i + 0.5) * dx, (j + 0.5) * dx, z, dx, rho0, eta, alpha, false), z);
      }
    }
  }
  problem.box.lower = {-0.5 * s.floor_cells * dx, 0.0, -0.5 * s.floor_cells * dx};
  problem.box.upper = {1.5 * s.floor_cells * dx, s.across_cells * dx, 1.5 * s.floor_cells * dx};
  problem.box.periodic = {false, true, false};
  return problem;
}

// The profile and its flank fit are common/flank_slope.hpp's, shared with the DEM piles.
using craterkit::flank_slope;
using craterkit::FlankFit;
using craterkit::SurfaceProfile;

// Free-surface height per column of width dx along x (over all y), from the highest moving particle:
// z_s = z_max + dx/2 (the top particle centre lies half a spacing below the surface). Columns holding
// fewer than half a layer (across_cells/2 particles) count as empty (z_s = 0): stray grains do not make
// a surface.
inline SurfaceProfile surface_profile(const Particles& p, const BlockSetup& s) {
  const double dx = s.spacing;
  const int columns = s.floor_cells;
  std::vector<double> top(columns, -1e300);
  std::vector<int> count(columns, 0);
  for (std::size_t k = 0; k < p.size(); ++k) {
    if ((p.flags[k] & particle_fixed) != 0 || p.material[k] != 0) continue;
    const int c = static_cast<int>(std::floor(p.x[k] / dx));
    if (c < 0 || c >= columns) continue;
    top[c] = std::max(top[c], p.z[k]);
    ++count[c];
  }
  SurfaceProfile out;
  for (int c = 0; c < columns; ++c) {
    out.x.push_back((c + 0.5) * dx);
    out.height.push_back(2 * count[c] >= s.across_cells ? top[c] + 0.5 * dx : 0.0);
  }
  return out;
}

// Run-out: the far edge of the last non-empty column, m from the back wall (x = 0).
inline double runout(const SurfaceProfile& profile, double dx) {
  double front = 0.0;
  for (std::size_t c = 0; c < profile.x.size(); ++c)
    if (profile.height[c] > 0.0) front = profile.x[c] + 0.5 * dx;
  return front;
}

// Root-mean-square speed of the granular particles, m/s: "at rest" is judged on it, so that a single
// grain still rattling at the toe does not count as flow.
inline double rms_speed(const Particles& p) {
  double v2 = 0.0;
  int n = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if ((p.flags[k] & particle_fixed) != 0 || p.material[k] != 0) continue;
    v2 += p.vx[k] * p.vx[k] + p.vy[k] * p.vy[k] + p.vz[k] * p.vz[k];
    ++n;
  }
  return n > 0 ? std::sqrt(v2 / n) : 0.0;
}

// Largest speed of the moving particles, m/s.
inline double max_speed(const Particles& p) {
  double v2 = 0.0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if ((p.flags[k] & particle_fixed) != 0 || p.material[k] != 0) continue;
    v2 = std::max(v2, p.vx[k] * p.vx[k] + p.vy[k] * p.vy[k] + p.vz[k] * p.vz[k]);
  }
  return std::sqrt(v2);
}

}  // namespace granular_test

namespace granular_test {

// An infinite slope in slope coordinates: a layer of depth_cells lattice cells on a floor (three elastic
// layers below z = 0 on three fixed ones, as above), periodic along x (downslope) and y, with gravity tilted
// by the slope angle beta: g = g (sin beta, 0, -cos beta). It starts in the static elastic state of the
// slope,
//   sigma_xz = rho g sin(beta) (D - z),  P = rho g cos(beta) (D - z),  other deviatoric components 0,
// which is in equilibrium; whether it stays there is decided by the yield criterion alone (no elastic
// overshoot from switching gravity on).
struct SlopeSetup {
  double spacing = 0.005;
  int length_cells = 8;  // periodic along x
  int across_cells = 7;  // periodic along y
  int depth_cells = 12;  // layer depth D
  double gravity = 9.81;
  double density = 1500.0;
  double sound_speed_factor = 10.0;  // bulk c = factor sqrt(g D)
  double poisson_ratio = 0.3;
  double friction = 0.55;
  double slope_degrees = 20.0;
};

inline double layer_depth(const SlopeSetup& s) {
  return s.depth_cells * s.spacing;
}

inline StandardProblemConfig slope_config(const SlopeSetup& s) {
  StandardProblemConfig config;
  const double beta = s.slope_degrees * std::numbers::pi / 180.0;
  config.simulation.solver.gravity = {s.gravity * std::sin(beta), 0.0, -s.gravity * std::cos(beta)};
  config.simulation.solver.viscosity.viscosity_switch = ViscositySwitch::morris_monaghan;
  config.simulation.solver.smoothing.neighbour_band = 1.0;
  config.simulation.solver.smoothing.max_smoothing_length =
      1.3 * config.simulation.solver.smoothing.eta * s.spacing;
  return config;
}

inline ProblemSetup make_slope(const SlopeSetup& s, const StandardProblemConfig& config) {
  const double dx = s.spacing, rho0 = s.density, g = s.gravity, D = layer_depth(s);
  const double c = s.sound_speed_factor * std::sqrt(g * D);
  const double K = rho0 * c * c;
  const double beta = s.slope_degrees * std::numbers::pi / 180.0;
  const double eta = config.simulation.solver.smoothing.eta,
               alpha = config.simulation.solver.viscosity.alpha_min;
  ProblemSetup problem;
  problem.materials = {solid_test::granular_material(rho0, K, s.poisson_ratio, s.friction, 0.0),
                       wall_material(rho0, K, s.poisson_ratio)};
  auto& p = problem.particles;
  for (int i = 0; i < s.length_cells; ++i) {
    for (int j = 0; j < s.across_cells; ++j) {
      for (int l = -6; l < s.depth_cells; ++l) {
        const double z = (l + 0.5) * dx;
        if (l < -3) {  // fixed backing
          solid_test::add_particle(p, (i + 0.5) * dx, (j + 0.5) * dx, z, dx, rho0, eta, alpha, true);
          continue;
        }
        // Granular layer and, for l < 0, the elastic floor layer under it in the same static state.
        const double pressure = rho0 * g * std::cos(beta) * (D - z);
        const auto k = solid_test::add_particle(p, (i + 0.5) * dx, (j + 0.5) * dx, z, dx,
                                                rho0 * (1.0 + pressure / K), eta, alpha, false);
        p.stress_xz[k] = rho0 * g * std::sin(beta) * (D - z);
        if (l < 0) p.material[k] = 1;
      }
    }
  }
  problem.box.lower = {0.0, 0.0, -10.0 * D};
  problem.box.upper = {s.length_cells * dx, s.across_cells * dx, 10.0 * D};
  problem.box.periodic = {true, true, false};
  return problem;
}

// Mean downslope velocity of the layer, m/s.
inline double mean_downslope_velocity(const Particles& p) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if ((p.flags[k] & particle_fixed) != 0 || p.material[k] != 0) continue;
    sum += p.vx[k];
    ++n;
  }
  return n > 0 ? sum / n : 0.0;
}

}  // namespace granular_test
