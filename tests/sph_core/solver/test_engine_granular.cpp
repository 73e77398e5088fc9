// Granular flow under gravity, the part CI runs: a vertical cut in a cohesive Lundborg material
// against the Rankine height (the cohesionless repose angles and run-outs are minutes-long runs, in
// test_engine_granular_slow.cpp), on an elastic floor backed by fixed particles (granular_setup.hpp). The
// material is the late-stage medium of docs/physics.md section 3: the linear low-sound-speed law with a bulk
// sound speed of 10 sqrt(g H) (so the flow stays below Mach ~0.15 and the static compression rho g H / A is 1
// %), Poisson's ratio 0.3, rho0 = 1500 kg/m^3, g = 9.81 m/s^2. Only the friction and the cohesion matter for
// the comparisons; the soft, slow medium keeps the runs at a few thousand steps. Docs: docs/validation.md,
// "Granular flow".
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "sph_core/granular_checks.hpp"

namespace {

using namespace granular_test;

// (a) Angle of repose and (b) run-out: minutes-long runs, in test_engine_granular_slow.cpp (label slow).

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
  const StandardProblemConfig config = block_config(s);
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
  Simulation sim(config.simulation.solver, std::move(problem));
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
