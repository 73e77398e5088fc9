// Which configuration changes a resume accepts (run_simulation.hpp, resume_configuration_difference): the
// listings are those TomlTable::values_read() writes into every checkpoint.
#include <gtest/gtest.h>

#include <string>

#include "craterkit/sph/run/run_simulation.hpp"

namespace craterkit::sph {
namespace {

const std::string checkpoint_listing =
    "impact.impact_speed = 2000\n"
    "impact.projectile_mass = 2\n"
    "run.end_time = 300\n"
    "output.snapshot_times = [1, 10]\n";

TEST(ResumeConfiguration, TheSameListingAgrees) {
  EXPECT_EQ(resume_configuration_difference(checkpoint_listing, checkpoint_listing), "");
}

TEST(ResumeConfiguration, EndTimeAndOutputMayChange) {
  const std::string now =
      "impact.impact_speed = 2000\n"
      "impact.projectile_mass = 2\n"
      "run.end_time = 500\n"
      "output.snapshot_times = [1, 10, 100]\n";
  EXPECT_EQ(resume_configuration_difference(checkpoint_listing, now), "");
}

TEST(ResumeConfiguration, AChangedValueIsNamedWithBothValues) {
  const std::string now =
      "impact.impact_speed = 2000.2\n"
      "impact.projectile_mass = 2\n"
      "run.end_time = 300\n";
  EXPECT_EQ(resume_configuration_difference(checkpoint_listing, now),
            "impact.impact_speed: 2000.2 now, 2000");
}

TEST(ResumeConfiguration, AKeyTheCheckpointDidNotKnowAgreesWhenTheFileLeavesItOut) {
  // A key added to the engine after the checkpoint was written: its default reproduces the older run.
  const std::string now = checkpoint_listing + "impact.far_radius = (absent)\n";
  EXPECT_EQ(resume_configuration_difference(checkpoint_listing, now), "");
}

TEST(ResumeConfiguration, AKeyTheCheckpointDidNotKnowIsRefusedWhenTheFileSetsIt) {
  const std::string now = checkpoint_listing + "impact.far_radius = 9\n";
  EXPECT_EQ(resume_configuration_difference(checkpoint_listing, now), "impact.far_radius: 9 now, (not read)");
}

TEST(ResumeConfiguration, AKeyTheEngineNoLongerReadsAgreesOnlyIfTheCheckpointLeftItOut) {
  EXPECT_EQ(
      resume_configuration_difference(checkpoint_listing + "impact.old_key = (absent)\n", checkpoint_listing),
      "");
  EXPECT_EQ(resume_configuration_difference(checkpoint_listing + "impact.old_key = 3\n", checkpoint_listing),
            "impact.old_key: (not read) now, 3");
}

}  // namespace
}  // namespace craterkit::sph
