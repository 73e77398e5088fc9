#pragma once
// Shared by the engine's physics tests: run a configuration to a time in memory, compare particle sets.
#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <type_traits>

#include "craterkit/sph/run/standard_problem_config.hpp"

namespace engine_test {

inline craterkit::sph::Simulation run_to(const craterkit::sph::StandardProblemConfig& config,
                                         double end_time) {
  craterkit::sph::Simulation sim(config.simulation.solver, craterkit::sph::build_standard_problem(config));
  while (sim.time() < end_time) sim.step(end_time);
  return sim;
}

// Every field of a equals the same field of b (operator==, so NaN never compares equal), and both hold
// the same fields (a field present in a only fails): the check of bitwise restarts.
inline void expect_identical_particles(const craterkit::sph::Particles& a,
                                       const craterkit::sph::Particles& b) {
  ASSERT_EQ(a.size(), b.size());
  a.for_each_field([&](std::string_view name, const auto& field) {
    bool same = false;
    b.for_each_field([&](std::string_view other, const auto& other_field) {
      if constexpr (std::is_same_v<decltype(field), decltype(other_field)>) {
        if (name == other) same = field == other_field;
      }
    });
    EXPECT_TRUE(same) << "field " << name << " differs";
  });
}

}  // namespace engine_test
