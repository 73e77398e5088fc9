// The DEM late stage end to end on a small synthetic hand-off: a quarter half-space of SPH material at rest
// around a bowl that flows outward and up, with a few fast ejecta above it, written as an impact run's
// snapshot; then a bed of 0.2 m grains settled under g = 1 m/s^2, the hand-off, LAMMPS until growth ends
// (about 4 s) and the crater on the grains. Checks that what LAMMPS starts from is what the hand-off reported
// (momentum, mass, energy of its first dump), that mass is kept (every dump plus the grains it lost is the
// hand-off's mass), that LAMMPS was stopped soon after the end of growth, and that crater.json is the
// measurement of the dump it names.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>

#include "craterkit/dem/lammps_files.hpp"
#include "craterkit/dem_late_stage/dem_late_stage.hpp"
#include "craterkit/dem_late_stage/grain_crater.hpp"
#include "craterkit/impact/impact_run_record.hpp"
#include "craterkit/sph/io/snapshot.hpp"
#include "sph_core/test_io_scratch_directory.hpp"

namespace craterkit::dem_late_stage {
namespace {

constexpr double rho = 1300.0;
constexpr double dx = 0.1;

// SPH material fills x, y in [0, 3], z in [-2.5, 0] except a bowl about the origin; inside 1.4 m the material
// moves outward and upward at up to 0.2 m/s; four particles fly up fast.
std::filesystem::path write_handoff_snapshot(const std::filesystem::path& folder) {
  sph::Particles p;
  auto add = [&](double x, double y, double z, double vx, double vy, double vz) {
    const std::size_t i = p.size();
    p.resize(i + 1);
    p.id[i] = i + 1;
    p.x[i] = x, p.y[i] = y, p.z[i] = z;
    p.vx[i] = vx, p.vy[i] = vy, p.vz[i] = vz;
    p.mass[i] = rho * dx * dx * dx;
    p.density[i] = rho;
    p.smoothing_length[i] = 1.2 * dx;
  };
  for (double x = 0.5 * dx; x < 3.0; x += dx)
    for (double y = 0.5 * dx; y < 3.0; y += dx)
      for (double z = -0.5 * dx; z > -2.5; z -= dx) {
        const double r = std::sqrt(x * x + y * y + z * z);
        // The bowl: a spherical cap of radius 1 m at the plane and 0.25 m deep (walls up to 28 deg steep: it
        // stands).
        constexpr double radius = 1.0, depth = 0.25;
        constexpr double centre = 0.5 * (radius * radius + depth * depth) / depth - depth;
        if (x * x + y * y + (z - centre) * (z - centre) < (centre + depth) * (centre + depth)) continue;
        const double speed = r < 1.4 ? 0.2 * (1.4 - r) / 0.6 : 0.0;
        add(x, y, z, speed * x / r, speed * y / r, speed * 0.5);
      }
  for (int k = 0; k < 4; ++k) add(0.3 + 0.2 * k, 0.4, 0.6, 0.5, 0.3, 2.0);
  impact::ImpactRunRecord record;
  record.initial_bulk_density = rho;
  record.initial_sound_speed = 100.0;
  record.particle_spacing = record.inner_spacing = dx;
  record.domain_radius = 5.0;
  record.fixed_shell_thickness = 2.4 * dx;
  record.gravity = 1.0;
  record.escape_speed = 1.0;
  record.symmetry = impact::DomainSymmetry::quarter;
  sph::RunAttributes attributes = impact::run_record_attributes(record);
  attributes.time = 0.5;
  const auto path = folder / "handoff.h5";
  sph::write_snapshot(path, p, attributes);
  return path;
}

MotionTotals dump_totals(const dem::Grains& grains) {
  MotionTotals t;
  t.count = grains.size();
  t.mass = dem::total_mass(grains);
  t.momentum = dem::total_momentum(grains);
  t.kinetic_energy = dem::kinetic_energy(grains);
  return t;
}

TEST(DemLateStage, LammpsStartsFromTheReportedHandOffKeepsMassAndTheCraterIsItsDumpsMeasurement) {
  test::ScratchDirectory scratch("dem_late_stage");
  DemLateStageSpec spec;
  spec.snapshot = write_handoff_snapshot(scratch.path());
  spec.grain_diameter = 0.2;
  spec.bed_length = 2.4;
  spec.bed_depth = 2.0;
  spec.bed_height = 0.4;
  spec.end_time = 10.0;
  spec.output_interval = 0.25;
  const auto out = scratch.path() / "run";
  const DemLateStageResult result = run_dem_late_stage(spec, out);
  const auto& b = result.balance;
  std::printf(
      "late stage: %zu grains (%zu moving, %zu flying), carved %zu; SPH in bed p_x %.4g, grains %.4g; "
      "KE SPH %.4g, grains %.4g J; crater %.3f m at %.2f s; settle %.0f s, LAMMPS %.0f s\n",
      result.grains, b.grains_moving.count, b.grains_flying.count, b.grains_carved, b.sph_in_bed.momentum[0],
      b.grains_moving.momentum[0], b.sph_in_bed.kinetic_energy, b.grains_moving.kinetic_energy,
      result.crater.crater_radius, result.crater_time, result.settle_seconds, result.lammps_seconds);

  // The four fast particles fly, one grain each.
  EXPECT_EQ(b.sph_flying.count, 4u);
  EXPECT_EQ(b.grains_flying.count, 4u);
  // The flow handed over: momentum outward and upward, within 20 % of the SPH material's (grains 0.2 m wide
  // average a flow that changes over 0.6 m).
  ASSERT_GT(b.sph_in_bed.momentum[0], 0.0);
  EXPECT_NEAR(b.grains_moving.momentum[0], b.sph_in_bed.momentum[0], 0.2 * b.sph_in_bed.momentum[0]);
  EXPECT_NEAR(b.grains_moving.momentum[2], b.sph_in_bed.momentum[2], 0.2 * b.sph_in_bed.momentum[2]);

  // LAMMPS's first dump (step 0) holds the grains as handed over.
  std::vector<long> ids;
  const dem::Grains first = dem::read_lammps_dump(out / "lammps" / "dumps" / "grains.0.dump", &ids);
  ASSERT_EQ(first.size(), result.grains);
  const MotionTotals all = dump_totals(first);
  const double handed_mass = b.grains_moving.mass + b.grains_frozen.mass + b.grains_flying.mass;
  EXPECT_NEAR(all.mass, handed_mass, 1e-12 * handed_mass);
  for (int k = 0; k < 3; ++k) {
    const double handed = b.grains_moving.momentum[k] + b.grains_flying.momentum[k];
    EXPECT_NEAR(all.momentum[k], handed, 1e-9 * std::abs(handed) + 1e-12) << "component " << k;
  }
  const double handed_energy = b.grains_moving.kinetic_energy + b.grains_flying.kinetic_energy;
  EXPECT_NEAR(all.kinetic_energy, handed_energy, 1e-9 * handed_energy);

  // Mass: the grains of the dump crater.json names plus those lost through the box's sides, top or bottom
  // are the hand-off's, and the ejected mass is the SPH run's, the lost grains' and the flying ones' (the
  // flying grains, without contacts, fall back through the bed here: g = 1 m/s^2 brings 2 m/s back).
  ASSERT_GE(result.samples.size(), 6u);
  const auto crater_json = nlohmann::json::parse(std::ifstream(out / "crater.json"));
  const double time = crater_json.at("time").get<double>();
  EXPECT_DOUBLE_EQ(time, result.crater_time);
  const long step = std::lround((time - 0.5) / result.time_step);
  const dem::Grains chosen =
      dem::read_lammps_dump(out / "lammps" / "dumps" / ("grains." + std::to_string(step) + ".dump"), &ids);
  double flying_left = 0.0;
  std::vector<int> roles;
  for (std::size_t g = 0; g < chosen.size(); ++g) {
    // The flying grains come last, after the bed's.
    roles.push_back(static_cast<std::size_t>(ids[g]) > b.grains_moving.count + b.grains_frozen.count
                        ? static_cast<int>(GrainRole::flying)
                        : static_cast<int>(GrainRole::moving));
    if (roles.back() == static_cast<int>(GrainRole::flying)) flying_left += chosen.mass(g);
  }
  const double lost = handed_mass - dem::total_mass(chosen);
  EXPECT_GE(lost, -1e-12 * handed_mass);
  EXPECT_NEAR(crater_json.at("ejected_mass").get<double>(), 4.0 * (b.sph_ejected.mass + lost + flying_left),
              1e-9 * handed_mass);
  // crater.json is the measurement of that dump.
  EXPECT_DOUBLE_EQ(crater_json.at("crater_radius").get<double>(), result.crater.crater_radius);
  EXPECT_TRUE(std::isfinite(result.crater.crater_radius));
  // The bowl was 1 m in radius at the plane; the outward flow only widens it.
  EXPECT_GT(result.crater.crater_radius, 1.0 - spec.grain_diameter);

  // Growth ended (the bed comes to rest within about 4 s) and LAMMPS was stopped at a dump soon after, long
  // before the end time; crater.json is the ended sample's.
  ASSERT_TRUE(result.growth_ended_sample.has_value());
  EXPECT_TRUE(result.stopped_when_grown);
  const auto& ended = result.samples[*result.growth_ended_sample];
  EXPECT_DOUBLE_EQ(result.crater_time, ended.time);
  EXPECT_EQ(ended.radius, result.crater.crater_radius);
  EXPECT_LT(result.samples.back().time, spec.end_time - 2.0);
  EXPECT_GE(result.samples.back().time, ended.time);
}

}  // namespace
}  // namespace craterkit::dem_late_stage
