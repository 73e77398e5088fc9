#pragma once
// Shared by the engine's physics tests: run a configuration to a time in memory.
#include <string>

#include "craterkit/sph/config.hpp"
#include "craterkit/sph/simulation.hpp"

namespace engine_test {

inline craterkit::sph::Simulation run_to(const craterkit::sph::SimulationConfig& config, double end_time) {
  craterkit::sph::Simulation sim(config, craterkit::sph::build_problem(config));
  while (sim.time() < end_time) sim.step(end_time);
  return sim;
}

}  // namespace engine_test
