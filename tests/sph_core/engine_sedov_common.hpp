#pragma once
// The Sedov-Taylor blast (E = 1, rho = 1, gamma = 5/3, t = 0.05) run and measured as in
// docs/validation.md: density binned in spherical shells of width 0.5 dx about the blast centre,
// the shock radius is where the binned profile, going outward from its peak, falls through
// (peak + ambient)/2, and the profile L1 error is the mean |rho_i - rho_Sedov(r_i)| over the
// particles within 1.2 r_s (the whole disturbed region). Density by kernel summation, as in
// data/examples/sedov.toml (summation_density.hpp; why: docs/validation.md).
#include <algorithm>
#include <cmath>
#include <vector>

#include "craterkit/sph/io/conservation_log.hpp"
#include "craterkit/sph/run/standard_problem_config.hpp"
#include "sph_core/engine_test_helpers.hpp"
#include "support/sedov.hpp"

namespace engine_test {

struct SedovMeasurement {
  double shock_radius;     // measured, m
  double analytic_radius;  // xi0 (E t^2 / rho)^(1/5)
  double peak_density;     // of the binned profile
  double profile_l1;       // mean |rho - rho_Sedov| within 1.2 r_s
  double energy_error;     // relative
  double momentum_error;   // relative
  std::uint64_t steps;
  double mean_neighbours;
  std::uint64_t particle_updates;
};

// density: summation (the example's) or continuity; block_levels: block time steps (0: global step).
inline SedovMeasurement run_sedov(
    int particles_per_side, craterkit::sph::DensityMethod density = craterkit::sph::DensityMethod::summation,
    int block_levels = 0) {
  using namespace craterkit::sph;
  StandardProblemConfig config;
  SedovSetup setup;
  setup.particles_per_side = particles_per_side;
  setup.blast_radius = 0.1;  // uniform deposit, as data/examples/sedov.toml
  config.problem = setup;
  config.simulation.run.end_time = 0.05;
  config.simulation.solver.smoothing.max_smoothing_length = 0.1;
  config.simulation.solver.density = density;
  config.simulation.solver.time_step.block_levels = block_levels;
  if (block_levels > 0) config.simulation.solver.neighbours.search.skin = 0.1;
  config.simulation.solver.viscosity.viscosity_switch = ViscositySwitch::morris_monaghan;
  auto sim = run_to(config, 0.05);
  const auto& p = sim.particles();
  const craterkit::test_support::SedovSolution sedov(5.0 / 3.0);
  SedovMeasurement m{};
  m.analytic_radius = sedov.shock_radius(1.0, 1.0, sim.time());
  const double dx = 1.0 / particles_per_side;
  const double width = 0.5 * dx;
  const auto bins = static_cast<std::size_t>(0.5 / width);
  std::vector<double> sum(bins, 0.0), count(bins, 0.0);
  double l1 = 0.0, l1_count = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r = std::sqrt(p.x[i] * p.x[i] + p.y[i] * p.y[i] + p.z[i] * p.z[i]);
    const auto b = static_cast<std::size_t>(r / width);
    if (b < bins) {
      sum[b] += p.density[i];
      count[b] += 1.0;
    }
    if (r < 1.2 * m.analytic_radius) {
      l1 += std::abs(p.density[i] - sedov.state(r, 1.0, 1.0, sim.time()).density);
      l1_count += 1.0;
    }
  }
  m.profile_l1 = l1 / l1_count;
  std::vector<double> profile(bins, 0.0);
  for (std::size_t b = 0; b < bins; ++b) profile[b] = count[b] > 0 ? sum[b] / count[b] : 0.0;
  const auto peak =
      static_cast<std::size_t>(std::max_element(profile.begin(), profile.end()) - profile.begin());
  m.peak_density = profile[peak];
  const double half = 0.5 * (m.peak_density + 1.0);
  m.shock_radius = 0.0;
  for (std::size_t b = peak; b + 1 < bins; ++b) {
    if (profile[b + 1] < half) {
      const double r0 = (b + 0.5) * width, r1 = (b + 1.5) * width;
      m.shock_radius = r0 + (half - profile[b]) * (r1 - r0) / (profile[b + 1] - profile[b]);
      break;
    }
  }
  const auto now = sim.conserved();
  m.energy_error = relative_energy_error(sim.initial_conserved(), now);
  m.momentum_error = relative_momentum_error(sim.initial_conserved(), now);
  m.steps = sim.step_count();
  m.mean_neighbours = sim.mean_neighbours();
  m.particle_updates = sim.particle_updates();
  return m;
}

}  // namespace engine_test
