// The simulate configuration: the shipped examples parse; unknown keys, wrong types, out-of-range
// values and mismatched set-up tables are InputErrors naming the key.
#include <gtest/gtest.h>

#include <string>

#include "craterkit/common/data_path.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/sph/io/config.hpp"
#include "craterkit/sph/solver/simulation.hpp"

using namespace craterkit::sph;
using craterkit::InputError;

namespace {

std::string error_of(const std::string& text) {
  try {
    parse_simulation_config(text, "test.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const std::string minimal = "[problem]\nsetup = \"sod\"\n[run]\nend_time = 0.2\n";

}  // namespace

TEST(SimulationConfig, ShippedExamplesParse) {
  for (const char* name : {"sedov.toml", "sod.toml", "plates.toml"}) {
    const auto config = load_simulation_config(craterkit::data_file(std::string("examples/") + name));
    EXPECT_GT(config.run.end_time, 0.0) << name;
  }
  const auto sedov = load_simulation_config(craterkit::data_file("examples/sedov.toml"));
  ASSERT_TRUE(std::holds_alternative<SedovSetup>(sedov.setup));
  EXPECT_EQ(std::get<SedovSetup>(sedov.setup).particles_per_side, 50);
  EXPECT_DOUBLE_EQ(sedov.run.end_time, 0.05);
}

TEST(SimulationConfig, DefaultsApply) {
  const auto c = parse_simulation_config(minimal, "test.toml");
  EXPECT_EQ(setup_name(c.setup), "sod");
  EXPECT_DOUBLE_EQ(c.viscosity.alpha, 1.0);
  EXPECT_DOUBLE_EQ(c.viscosity.beta, 2.0);
  EXPECT_DOUBLE_EQ(c.time_step.courant, 0.3);
  EXPECT_EQ(c.kernel, KernelType::cubic_spline);
}

TEST(SimulationConfig, DensityMethodIsChosenInTheKernelTable) {
  EXPECT_EQ(parse_simulation_config(minimal, "t.toml").density, DensityMethod::continuity);
  EXPECT_EQ(parse_simulation_config(minimal + "[kernel]\ndensity = \"summation\"\n", "t.toml").density,
            DensityMethod::summation);
}

TEST(SimulationConfig, UnknownKeysAreNamed) {
  EXPECT_NE(error_of(minimal + "[viscosity]\nalpah = 1.0\n").find("viscosity.alpah"), std::string::npos);
  EXPECT_NE(error_of(minimal + "[bogus]\nx = 1\n").find("bogus"), std::string::npos);
  EXPECT_NE(error_of(minimal + "[sod]\nleft_pressur = 1\n").find("sod.left_pressur"), std::string::npos);
}

TEST(SimulationConfig, OutOfRangeAndWrongTypesAreNamed) {
  const auto courant = error_of(minimal + "[time_step]\ncourant = 1.5\n");
  EXPECT_NE(courant.find("time_step.courant"), std::string::npos);
  EXPECT_NE(courant.find("1.5"), std::string::npos);
  EXPECT_NE(error_of(minimal + "[viscosity]\nswitch = \"magic\"\n").find("viscosity.switch"),
            std::string::npos);
  EXPECT_NE(error_of(minimal + "[kernel]\neta = \"big\"\n").find("kernel.eta"), std::string::npos);
  EXPECT_NE(error_of(minimal + "[kernel]\ndensity = \"sph\"\n").find("kernel.density"), std::string::npos);
  EXPECT_NE(error_of("[problem]\nsetup = \"sod\"\n[run]\nend_time = -1\n").find("run.end_time"),
            std::string::npos);
  EXPECT_NE(error_of("[problem]\nsetup = \"sod\"\n").find("run.end_time"), std::string::npos);
  EXPECT_NE(error_of(minimal + "[output]\nsnapshot_times = [0.1, 0.05]\n").find("output.snapshot_times"),
            std::string::npos);
  EXPECT_NE(error_of(minimal + "[run]\n").find("TOML"), std::string::npos);  // duplicate table
}

// The artificial stress: epsilon in [0, 1], off by default; a problem without a solid material refuses it
// when the simulation is built (the materials are known only then).
TEST(SimulationConfig, ArtificialStress) {
  EXPECT_DOUBLE_EQ(parse_simulation_config(minimal, "t.toml").artificial_stress, 0.0);
  EXPECT_DOUBLE_EQ(
      parse_simulation_config(minimal + "[artificial_stress]\nepsilon = 0.3\n", "t.toml").artificial_stress,
      0.3);
  const auto too_big = error_of(minimal + "[artificial_stress]\nepsilon = 2\n");
  EXPECT_NE(too_big.find("artificial_stress.epsilon"), std::string::npos);
  EXPECT_NE(too_big.find("2"), std::string::npos);
  const auto config = parse_simulation_config(minimal + "[artificial_stress]\nepsilon = 0.3\n", "t.toml");
  try {
    Simulation sim(config, build_problem(config));
    ADD_FAILURE() << "a gas problem with artificial stress was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("artificial_stress.epsilon"), std::string::npos) << e.what();
  }
}

TEST(SimulationConfig, SetupTableMustMatchTheProblem) {
  EXPECT_NE(error_of(minimal + "[sedov]\nparticles_per_side = 20\n").find("[sedov]"), std::string::npos);
  EXPECT_NE(error_of("[problem]\nsetup = \"blast\"\n[run]\nend_time = 1\n").find("problem.setup"),
            std::string::npos);
}
