// Sod shock tube (3D, thin periodic box) against the exact Riemann solution (Toro 2009, ch. 4):
// the L1 density error over |x| < 0.5 at t = 0.2 falls with resolution; momentum is conserved to
// round-off and total energy to the time-integration error.
//
// Resolution: the left gas expands by 1/0.426 = 2.35 along x only, so in the star region its
// lattice planes are 2.35 initial spacings apart while h = eta (m/rho)^(1/3) grows by only 1.33. With
// eta = 1.2 the kernel (support 2h) then spans too few planes along x: the pressure gradient is
// biased, and the star state came out wrong by a resolution-independent amount (left plateau
// P = 0.41, contact at 0.83 instead of p* = 0.303, u* = 0.927; L1 0.038 -> 0.034). eta = 1.5 (h = 0.85
// plane spacings in the star gas) gives p* and u* within 2 % (docs/validation.md lists the
// measurements for eta = 1.2 ... 2.0); the cross-section is widened to keep 4 h inside the period.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "craterkit/sph/io/conservation_log.hpp"
#include "craterkit/sph/run/standard_problem_config.hpp"
#include "sph_core/engine_test_helpers.hpp"
#include "support/exact_riemann.hpp"

using namespace craterkit::sph;
using craterkit::test_support::ExactRiemannSolver;
using craterkit::test_support::GasState;

namespace {

struct SodResult {
  double l1_density;
  double star_pressure;  // mean over the left star plateau, -0.04 < x < 0.12
  double star_velocity;
  double energy_error;
  double momentum_error;
  double particles;
};

SodResult run_sod(int left_per_length) {
  StandardProblemConfig config;
  SodSetup setup;
  setup.left_particles_per_length = left_per_length;
  setup.cross_section = 16.0 / left_per_length;  // 16 left, 8 right lattice cells across (> 4 h)
  config.problem = setup;
  config.simulation.solver.smoothing.eta =
      1.5;  // resolves the star gas, stretched 2.35x along x only (see the header)
  config.simulation.run.end_time = 0.2;
  config.simulation.solver.viscosity.viscosity_switch = ViscositySwitch::morris_monaghan;
  auto sim = engine_test::run_to(config, 0.2);
  const ExactRiemannSolver exact(1.4, GasState{1.0, 0.0, 1.0}, GasState{0.125, 0.0, 0.1});
  const auto& p = sim.particles();
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (std::abs(p.x[i]) >= 0.5) continue;
    sum += std::abs(p.density[i] - exact.sample(p.x[i] / sim.time()).density);
    ++count;
  }
  double pressure = 0.0, velocity = 0.0, plateau = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.x[i] > -0.04 && p.x[i] < 0.12) {
      pressure += p.pressure[i];
      velocity += p.vx[i];
      plateau += 1.0;
    }
  }
  const auto now = sim.conserved();
  return {sum / static_cast<double>(count),
          pressure / plateau,
          velocity / plateau,
          relative_energy_error(sim.initial_conserved(), now),
          std::abs(now.momentum_x - sim.initial_conserved().momentum_x) / now.absolute_momentum,
          static_cast<double>(p.size())};
}

}  // namespace

TEST(SodShockTube, DensityErrorFallsWithResolution) {
  const SodResult coarse = run_sod(50);
  const SodResult fine = run_sod(100);
  std::printf("Sod L1(rho): %.5f (50/length, %.0f particles), %.5f (100/length, %.0f particles)\n",
              coarse.l1_density, coarse.particles, fine.l1_density, fine.particles);
  std::printf("Sod energy error %.2e, momentum error %.2e\n", fine.energy_error, fine.momentum_error);
  EXPECT_LT(fine.l1_density, coarse.l1_density);
  EXPECT_LT(fine.l1_density, 0.012);  // measured 0.0116 (0.0200 at 50 per length)
  EXPECT_LT(fine.energy_error, 1e-4);
  EXPECT_LT(fine.momentum_error, 1e-12);
}

TEST(SodShockTube, StarStateMatchesTheExactSolution) {
  const SodResult fine = run_sod(100);
  const ExactRiemannSolver exact(1.4, GasState{1.0, 0.0, 1.0}, GasState{0.125, 0.0, 0.1});
  std::printf("Sod star state: P %.4f (exact %.4f), u %.4f (exact %.4f)\n", fine.star_pressure,
              exact.star().pressure, fine.star_velocity, exact.star().velocity);
  EXPECT_NEAR(fine.star_pressure / exact.star().pressure, 1.0, 0.05);
  EXPECT_NEAR(fine.star_velocity / exact.star().velocity, 1.0, 0.05);
}
