#pragma once
// Shared by the impact tests: run an impact configuration to a time in memory.
#include "craterkit/impact/impact_run.hpp"
#include "craterkit/sph/solver/simulation.hpp"

namespace impact_test {

inline craterkit::sph::Simulation run_to(const craterkit::impact::ImpactConfig& config, double end_time) {
  craterkit::sph::Simulation sim(config.simulation.solver,
                                 craterkit::impact::build_impact_run(config).problem);
  while (sim.time() < end_time) sim.step(end_time);
  return sim;
}

}  // namespace impact_test
