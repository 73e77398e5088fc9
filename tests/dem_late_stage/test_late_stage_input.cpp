// Bad input to the DEM late stage is refused before anything is written, naming what is wrong.
#include <gtest/gtest.h>

#include <string>

#include "craterkit/common/input_error.hpp"
#include "craterkit/dem_late_stage/dem_late_stage.hpp"
#include "craterkit/impact/impact_run_record.hpp"
#include "craterkit/sph/io/snapshot.hpp"
#include "sph_core/test_io_scratch_directory.hpp"

namespace craterkit::dem_late_stage {
namespace {

std::string refusal(const DemLateStageSpec& spec, const std::filesystem::path& out) {
  try {
    (void)run_dem_late_stage(spec, out);
  } catch (const InputError& e) {
    EXPECT_FALSE(std::filesystem::exists(out)) << "wrote " << out;
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

sph::Particles one_particle() {
  sph::Particles p;
  p.resize(1);
  p.mass[0] = 1.0;
  p.density[0] = 1.0;
  p.smoothing_length[0] = 1.0;
  return p;
}

TEST(DemLateStageInput, RefusesBadValuesMissingFilesAndRunsItCannotContinue) {
  test::ScratchDirectory scratch("dem_late_stage_input");
  const auto out = scratch.path() / "out";
  DemLateStageSpec spec;
  spec.snapshot = scratch.path() / "missing.h5";
  EXPECT_NE(refusal(spec, out).find("missing.h5"), std::string::npos);

  spec.grain_diameter = 2.0;  // a 10 m bed would be 5 grains wide
  spec.bed_length = 10.0;
  EXPECT_NE(refusal(spec, out).find("bed_length"), std::string::npos);
  spec.grain_diameter = 0.5;
  spec.bed_length = 0.0;  // the run's domain radius
  spec.restitution = 0.0;
  EXPECT_NE(refusal(spec, out).find("restitution"), std::string::npos);
  spec.restitution = 0.5;

  // Not an impact run.
  spec.snapshot = scratch.path() / "plain.h5";
  sph::write_snapshot(spec.snapshot, one_particle(), sph::RunAttributes{});
  EXPECT_NE(refusal(spec, out).find("not the snapshot of an impact run"), std::string::npos);

  // A full-domain impact run, then a quarter one with an angle of repose outside the calibration.
  impact::ImpactRunRecord record;
  record.initial_bulk_density = 1300.0;
  record.gravity = 1.0;
  record.escape_speed = 1.0;
  record.domain_radius = 15.0;
  spec.snapshot = scratch.path() / "full.h5";
  sph::write_snapshot(spec.snapshot, one_particle(), impact::run_record_attributes(record));
  EXPECT_NE(refusal(spec, out).find("quarter"), std::string::npos);
  record.symmetry = impact::DomainSymmetry::quarter;
  spec.snapshot = scratch.path() / "quarter.h5";
  sph::write_snapshot(spec.snapshot, one_particle(), impact::run_record_attributes(record));
  spec.repose_angle = 50.0;
  EXPECT_NE(refusal(spec, out).find("angle of repose 50"), std::string::npos);
  spec.repose_angle = 29.24;
  spec.end_time = 0.0;
  EXPECT_NE(refusal(spec, out).find("end_time"), std::string::npos);
  // A domain too small for ten grains across.
  spec.end_time = 500.0;
  record.domain_radius = 3.0;
  sph::write_snapshot(spec.snapshot, one_particle(), impact::run_record_attributes(record));
  EXPECT_NE(refusal(spec, out).find("bed_length: value 3 m"), std::string::npos);
}

}  // namespace
}  // namespace craterkit::dem_late_stage
