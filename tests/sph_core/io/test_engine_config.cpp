// The simulate configuration: the shipped examples parse; unknown keys, wrong types, out-of-range
// values and mismatched set-up tables are InputErrors naming the key.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "craterkit/common/data_path.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/common/toml_table.hpp"
#include "craterkit/sph/run/standard_problem_config.hpp"

using namespace craterkit::sph;
using craterkit::InputError;

namespace {

std::string error_of(const std::string& text) {
  try {
    parse_standard_problem_config(text, "test.toml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

StandardProblemConfig parse_file(const std::filesystem::path& path) {
  craterkit::TomlTable root = craterkit::TomlTable::parse_file(path);
  return parse_standard_problem_config(root);
}

StandardProblemConfig parse(const std::string& text) {
  return parse_standard_problem_config(text, "test.toml");
}

const std::string minimal = "[problem]\nsetup = \"sod\"\n[run]\nend_time = 0.2\n";

}  // namespace

TEST(StandardProblemConfig, ShippedExamplesParse) {
  for (const char* name : {"sedov.toml", "sod.toml", "plates.toml"}) {
    const auto config = parse_file(craterkit::data_file(std::string("examples/") + name));
    EXPECT_GT(config.simulation.run.end_time, 0.0) << name;
  }
  const auto sedov = parse_file(craterkit::data_file("examples/sedov.toml"));
  ASSERT_TRUE(std::holds_alternative<SedovSetup>(sedov.problem));
  EXPECT_EQ(std::get<SedovSetup>(sedov.problem).particles_per_side, 50);
  EXPECT_DOUBLE_EQ(sedov.simulation.run.end_time, 0.05);
}

TEST(StandardProblemConfig, DefaultsApply) {
  const auto c = parse(minimal);
  EXPECT_EQ(setup_name(c.problem), "sod");
  EXPECT_DOUBLE_EQ(c.simulation.solver.viscosity.alpha, 1.0);
  EXPECT_DOUBLE_EQ(c.simulation.solver.viscosity.beta, 2.0);
  EXPECT_DOUBLE_EQ(c.simulation.solver.time_step.courant, 0.3);
  EXPECT_EQ(c.simulation.solver.kernel, KernelType::cubic_spline);
  EXPECT_EQ(c.simulation.solver.time_step.block_levels, 0);
  EXPECT_EQ(c.simulation.solver.viscosity.viscosity_switch, ViscositySwitch::none);
}

TEST(StandardProblemConfig, DensityMethodIsChosenInTheKernelTable) {
  EXPECT_EQ(parse(minimal).simulation.solver.density, DensityMethod::continuity);
  EXPECT_EQ(parse(minimal + "[kernel]\ndensity = \"summation\"\n").simulation.solver.density,
            DensityMethod::summation);
}

TEST(StandardProblemConfig, UnknownKeysAreNamed) {
  EXPECT_NE(error_of(minimal + "[viscosity]\nalpah = 1.0\n").find("viscosity.alpah"), std::string::npos);
  EXPECT_NE(error_of(minimal + "[bogus]\nx = 1\n").find("bogus"), std::string::npos);
  EXPECT_NE(error_of(minimal + "[sod]\nleft_pressur = 1\n").find("sod.left_pressur"), std::string::npos);
}

TEST(StandardProblemConfig, OutOfRangeAndWrongTypesAreNamed) {
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
  EXPECT_NE(error_of(minimal + "[neighbours]\nhalo_skin = -0.1\n").find("neighbours.halo_skin"),
            std::string::npos);
  EXPECT_DOUBLE_EQ(parse(minimal + "[neighbours]\nhalo_skin = 0.3\n").simulation.solver.neighbours.halo_skin,
                   0.3);
}

// The artificial stress: epsilon in [0, 1], off by default; a problem without a solid material refuses it
// when the simulation is built (the materials are known only then).
TEST(StandardProblemConfig, ArtificialStress) {
  EXPECT_DOUBLE_EQ(parse(minimal).simulation.solver.artificial_stress, 0.0);
  EXPECT_DOUBLE_EQ(
      parse(minimal + "[artificial_stress]\nepsilon = 0.3\n").simulation.solver.artificial_stress, 0.3);
  const auto too_big = error_of(minimal + "[artificial_stress]\nepsilon = 2\n");
  EXPECT_NE(too_big.find("artificial_stress.epsilon"), std::string::npos);
  EXPECT_NE(too_big.find("2"), std::string::npos);
  const auto config = parse(minimal + "[artificial_stress]\nepsilon = 0.3\n");
  try {
    Simulation sim(config.simulation.solver, build_standard_problem(config));
    ADD_FAILURE() << "a gas problem with artificial stress was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("artificial_stress.epsilon"), std::string::npos) << e.what();
  }
}

TEST(StandardProblemConfig, SetupTableMustMatchTheProblem) {
  EXPECT_NE(error_of(minimal + "[sedov]\nparticles_per_side = 20\n").find("[sedov]"), std::string::npos);
  EXPECT_NE(error_of("[problem]\nsetup = \"blast\"\n[run]\nend_time = 1\n").find("problem.setup"),
            std::string::npos);
}

TEST(StandardProblemConfig, ImpactTablesAreRefused) {
  EXPECT_NE(error_of(minimal + "[crater]\ncheck_interval = 1\n").find("[crater]"), std::string::npos);
  EXPECT_NE(error_of("[problem]\nsetup = \"impact\"\n[run]\nend_time = 1\n").find("problem.setup"),
            std::string::npos);
}

// Checkpoints by wall clock need curve sorts: without them a checkpoint has to rebuild the neighbour lists,
// and at wall-clock moments the result would depend on the machine's load (run_simulation.hpp). The default
// interval (600 s) is refused with sort_interval = 0 too, naming both keys; checkpoints by step count are
// allowed.
TEST(StandardProblemConfig, WallClockCheckpointsNeedCurveSorts) {
  const std::string unsorted = minimal + "[neighbours]\nsort_interval = 0\n";
  for (const std::string& text : {unsorted, unsorted + "[output]\ncheckpoint_interval_seconds = 60\n"}) {
    const std::string message = error_of(text);
    EXPECT_NE(message.find("test.toml: output.checkpoint_interval_seconds = "), std::string::npos) << message;
    EXPECT_NE(message.find("neighbours.sort_interval = 0 is not allowed"), std::string::npos) << message;
  }
  const auto by_steps =
      parse(unsorted + "[output]\ncheckpoint_interval_seconds = 0\ncheckpoint_interval_steps = 7\n");
  EXPECT_EQ(by_steps.simulation.solver.neighbours.sort_interval, 0u);
  EXPECT_EQ(by_steps.simulation.output.checkpoint_interval_steps, 7u);
  EXPECT_EQ(parse(minimal + "[output]\ncheckpoint_interval_seconds = 60\n")
                .simulation.output.checkpoint_interval_seconds,
            60.0);
}
