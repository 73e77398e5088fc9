// The parts of the DEM late stage that do not settle anything: the contact law's checks and its LAMMPS model,
// the data and dump files read and written by LAMMPS itself, LAMMPS failures, the bed's cache key.
#include <gtest/gtest.h>

#include <chrono>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <numbers>
#include <random>
#include <string>

#include "craterkit/common/input_error.hpp"
#include "craterkit/dem/column_collapse.hpp"
#include "craterkit/dem/grain_contact.hpp"
#include "craterkit/dem/granular_bed.hpp"
#include "craterkit/dem/lammps_files.hpp"
#include "craterkit/dem/lammps_process.hpp"
#include "craterkit/dem/repose_calibration.hpp"
#include "sph_core/test_io_scratch_directory.hpp"

namespace craterkit::dem {
namespace {

std::string input_error_of(const auto& call) {
  try {
    call();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no InputError";
}

TEST(GrainContact, OutOfRangeValuesNameTheirKey) {
  GrainContact contact;
  EXPECT_NO_THROW(check_grain_contact(contact, "late_stage.dem"));
  contact.restitution = 1.5;
  EXPECT_EQ(input_error_of([&] { check_grain_contact(contact, "late_stage.dem"); }),
            "late_stage.dem.restitution: value 1.5 out of range: allowed (0, 1]");
  contact = GrainContact{};
  contact.sliding_friction = -0.1;
  EXPECT_NE(input_error_of([&] { check_grain_contact(contact, "t"); }).find("t.sliding_friction: value -0.1"),
            std::string::npos);
  contact = GrainContact{};
  contact.poisson_ratio = 0.5;
  EXPECT_NE(input_error_of([&] { check_grain_contact(contact, "t"); }).find("t.poisson_ratio"),
            std::string::npos);
}

TEST(GrainContact, HertzContactTimeFollowsItsScaling) {
  // t_c ~ m^(2/5) R^(-1/5) E*^(-2/5) v^(-1/5): at fixed density m ~ d^3, so t_c ~ d (Johnson 1985,
  // sec. 11.4).
  GrainContact contact;
  const double t1 = hertz_contact_time(contact, 0.01, 2500, 1.0);
  EXPECT_NEAR(hertz_contact_time(contact, 0.02, 2500, 1.0) / t1, 2.0, 1e-12);
  EXPECT_NEAR(hertz_contact_time(contact, 0.01, 2500, 32.0) / t1, 0.5, 1e-12);
  contact.youngs_modulus *= 32.0;
  EXPECT_NEAR(hertz_contact_time(contact, 0.01, 2500, 1.0) / t1, std::pow(32.0, -0.4), 1e-12);
}

TEST(GrainContact, ModulusForAnOverlapGivesThatHertzOverlap) {
  // f = pi d^2 P / (phi Z), delta = (3 f / (4 E* sqrt(d/4)))^(2/3): the modulus returned reproduces the
  // overlap.
  const double d = 0.4, rho_b = 1200, rho_g = 2400, g = 1.4e-4, depth = 7.0, nu = 0.25;
  const double modulus = youngs_modulus_for_overlap(rho_b, rho_g, g, depth, d, nu, 1e-3);
  const double force = std::numbers::pi * d * d * rho_b * g * depth / (0.5 * 5.0);
  const double effective = modulus / (2.0 * (1.0 - nu * nu));
  const double overlap = std::pow(3.0 * force / (4.0 * effective * std::sqrt(0.25 * d)), 2.0 / 3.0);
  EXPECT_NEAR(overlap / d, 1e-3, 1e-15);
  // Ten times the load needs 10 times the modulus for the same overlap; a tenth of the overlap 10^1.5 times
  // it.
  EXPECT_NEAR(youngs_modulus_for_overlap(rho_b, rho_g, 10 * g, depth, d, nu, 1e-3) / modulus, 10.0, 1e-12);
  EXPECT_NEAR(youngs_modulus_for_overlap(rho_b, rho_g, g, depth, d, nu, 1e-4) / modulus, std::pow(10.0, 1.5),
              1e-9);
}

TEST(GrainContact, ModelCarriesEveryFrictionToLammps) {
  GrainContact contact;
  contact.sliding_friction = 0.61;
  contact.rolling_friction = 0.07;
  const std::string model = lammps_contact_model(contact, 0.01, 2500);
  EXPECT_NE(model.find("tangential mindlin NULL 1.0 0.60999999999999999"), std::string::npos) << model;
  EXPECT_NE(model.find(" 0.070000000000000007 twisting marshall damping tsuji"), std::string::npos) << model;
  EXPECT_EQ(model.rfind("hertz/material 10000000 0.5 0.29999999999999999 ", 0), 0U) << model;
}

Grains some_grains(std::size_t n) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  Grains grains;
  for (std::size_t i = 0; i < n; ++i) {
    grains.add(0.05 + 0.1 * u(random), 0.05 + 0.1 * u(random), 0.01 + 0.2 * u(random),
               0.008 + 0.004 * u(random), 2000 + 1000 * u(random));
    grains.vx.back() = u(random) - 0.5;
    grains.vy.back() = u(random) - 0.5;
    grains.vz.back() = u(random) - 0.5;
    grains.omega_x.back() = 10 * (u(random) - 0.5);
    grains.omega_y.back() = 10 * (u(random) - 0.5);
    grains.omega_z.back() = 10 * (u(random) - 0.5);
  }
  return grains;
}

TEST(GrainContact, ModulusForAnImpactStoresTheImpactsEnergyAtThatOverlap) {
  // At the largest overlap of a Hertz impact the relative motion's kinetic energy m* v^2 / 2 is all elastic
  // energy: the modulus for an overlap and the contact's energy at that overlap agree.
  const double d = 0.5, rho_g = 2400, speed = 0.37, nu = 0.3;
  GrainContact contact;
  contact.poisson_ratio = nu;
  contact.youngs_modulus = youngs_modulus_for_impact(d, rho_g, speed, nu, 0.05);
  const double reduced_mass = 0.5 * rho_g * std::numbers::pi * d * d * d / 6.0;
  EXPECT_NEAR(hertz_elastic_energy(contact, 0.25 * d, 0.05 * d), 0.5 * reduced_mass * speed * speed,
              1e-12 * reduced_mass * speed * speed);
  // Twice the speed needs four times the modulus for the same overlap.
  EXPECT_NEAR(youngs_modulus_for_impact(d, rho_g, 2 * speed, nu, 0.05) / contact.youngs_modulus, 4.0, 1e-12);
}

TEST(GrainContact, TheElasticEnergyOfABedIsTheSumOverItsOverlappingPairs) {
  GrainContact contact;
  Grains grains;
  grains.add(0.0, 0.0, 0.0, 0.1, 2500);
  grains.add(0.099, 0.0, 0.0, 0.1, 2500);   // overlaps the first by 1 mm
  grains.add(0.0, 0.0, 0.0995, 0.1, 2500);  // overlaps the first by 0.5 mm, the second not
  grains.add(0.5, 0.5, 0.5, 0.2, 2500);     // alone
  const double expected =
      hertz_elastic_energy(contact, 0.025, 1e-3) + hertz_elastic_energy(contact, 0.025, 5e-4);
  EXPECT_NEAR(contact_elastic_energy(grains, contact), expected, 1e-9 * expected);
}

TEST(LammpsFiles, LammpsReadsTheDataFileAndItsDumpReadsBackTheSameGrains) {
  const test::ScratchDirectory folder("dem");
  const Grains grains = some_grains(50);
  write_lammps_data(folder.path() / "grains.data", grains, Box{0, 0.2, 0, 0.2, 0, 0.25});
  {
    std::ofstream script(folder.path() / "copy.in");
    script << "units si\natom_style sphere\natom_modify map array\nboundary p p f\nread_data grains.data\n"
           << "write_dump all custom copy.dump " << dump_columns << " modify sort id format float %.17g\n";
  }
  run_lammps({folder.path(), "copy.in", 1});
  const Grains back = read_lammps_dump(folder.path() / "copy.dump");
  ASSERT_EQ(back.size(), grains.size());
  for (std::size_t i = 0; i < grains.size(); ++i) {
    EXPECT_EQ(back.x[i], grains.x[i]);
    EXPECT_EQ(back.z[i], grains.z[i]);
    EXPECT_EQ(back.vy[i], grains.vy[i]);
    EXPECT_EQ(back.omega_z[i], grains.omega_z[i]);
    EXPECT_EQ(back.diameter[i], grains.diameter[i]);
    // LAMMPS stores the mass; the density comes back from it.
    EXPECT_NEAR(back.density[i], grains.density[i], 1e-12 * grains.density[i]);
  }
  EXPECT_NEAR(total_mass(back), total_mass(grains), 1e-12 * total_mass(grains));
}

TEST(LammpsProcess, RunsUnderMpirunOverTwoProcesses) {
  // Open MPI refuses root (CI containers) unless told; cross-memory attach is refused in some containers.
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT", "1", 0);
  ::setenv("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1", 0);
  ::setenv("OMPI_MCA_btl_vader_single_copy_mechanism", "none", 0);
  const test::ScratchDirectory folder("dem");
  const Grains grains = some_grains(40);
  write_lammps_data(folder.path() / "grains.data", grains, Box{0, 0.2, 0, 0.2, 0, 0.25});
  std::ofstream(folder.path() / "copy.in")
      << "units si\natom_style sphere\natom_modify map array\nboundary p p f\nread_data grains.data\n"
      << "run 0\n"
      << "write_dump all custom copy.dump " << dump_columns << " modify sort id format float %.17g\n";
  run_lammps({folder.path(), "copy.in", 2});
  std::ifstream log(folder.path() / "copy.log");
  const std::string text((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find(" on 2 procs for 0 steps"), std::string::npos) << text;
  const Grains back = read_lammps_dump(folder.path() / "copy.dump");
  ASSERT_EQ(back.size(), grains.size());
  for (std::size_t i = 0; i < grains.size(); ++i) EXPECT_EQ(back.y[i], grains.y[i]);
}

TEST(LammpsFiles, ADumpWithOtherColumnsIsRefusedNamingFileAndLine) {
  const test::ScratchDirectory folder("dem");
  const auto path = folder.path() / "other.dump";
  std::ofstream(path)
      << "ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n1\nITEM: BOX BOUNDS pp pp pp\n0 1\n0 1\n0 1\n"
      << "ITEM: ATOMS id x y z\n1 0.5 0.5 0.5\n";
  try {
    (void)read_lammps_dump(path);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(
        std::string(e.what()).find(path.string() + ":9: not a craterkit grain dump: columns 'id x y z'"),
        std::string::npos)
        << e.what();
  }
}

TEST(LammpsProcess, LastThermoValuesAreTheLastLineOfThatManyNumbers) {
  const test::ScratchDirectory folder("dem");
  const auto log = folder.path() / "run.log";
  EXPECT_TRUE(last_thermo_values(log, 3).empty());  // no log yet
  std::ofstream(log)
      << "thermo 100\n   Step          Atoms         KinEng    \n         0          1458   6.5         \n"
      << "       100          1457   5.25        \nPer MPI rank memory allocation (min/avg/max) = 13 | 13 | "
         "13\n"
      << "       200          1457   4.5  0.1\nLoop time of 1.5 on 1 procs for 200 steps with 1457 atoms\n";
  EXPECT_EQ(last_thermo_values(log, 3), (std::vector<double>{100, 1457, 5.25}));
  EXPECT_EQ(last_thermo_values(log, 4), (std::vector<double>{200, 1457, 4.5, 0.1}));
  EXPECT_TRUE(last_thermo_values(log, 5).empty());
}

TEST(LammpsProcess, PollIsCalledWhileItRunsAndWhatItThrowsStopsTheRun) {
  // A grain flying on for 2e9 steps (minutes): the poll sees the log grow, then throws; the run must end at
  // once with the poll's exception, the process gone.
  const test::ScratchDirectory folder("dem");
  std::ofstream(folder.path() / "long.in")
      << "units si\natom_style sphere\nregion box block 0 1 0 1 0 1\ncreate_box 1 box\n"
      << "create_atoms 1 single 0.5 0.5 0.5\nset type 1 diameter 0.1 density 1000\nfix move all nve/sphere\n"
      << "thermo 100000\nthermo_modify flush yes\nrun 2000000000\n";
  int calls = 0;
  LammpsPoll poll;
  poll.interval = std::chrono::milliseconds(200);
  poll.call = [&] {
    if (++calls == 3) throw std::runtime_error("enough");
  };
  const auto start = std::chrono::steady_clock::now();
  try {
    run_lammps({folder.path(), "long.in", 1}, poll);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "enough");
  }
  EXPECT_EQ(calls, 3);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 30.0);
}

TEST(LammpsProcess, AFailedRunQuotesTheLammpsErrorAndItsLog) {
  const test::ScratchDirectory folder("dem");
  std::ofstream(folder.path() / "bad.in") << "units si\natom_style no_such_style\n";
  try {
    run_lammps({folder.path(), "bad.in", 1});
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("ERROR"), std::string::npos) << what;
    EXPECT_NE(what.find("no_such_style"), std::string::npos) << what;
    EXPECT_NE(what.find((folder.path() / "bad.log").string()), std::string::npos) << what;
  }
}

TEST(LammpsProcess, AProgramThatFailsWithoutALogIsQuotedFromItsErrorOutput) {
  const test::ScratchDirectory folder("dem");
  const auto fake = folder.path() / "fake_lmp";
  std::ofstream(fake) << "#!/bin/sh\necho 'not enough slots available' >&2\nexit 3\n";
  std::filesystem::permissions(fake, std::filesystem::perms::owner_all);
  std::ofstream(folder.path() / "any.in") << "units si\n";
  ::setenv("CRATERKIT_LAMMPS", fake.c_str(), 1);
  std::string what;
  try {
    run_lammps({folder.path(), "any.in", 1});
  } catch (const std::runtime_error& e) {
    what = e.what();
  }
  ::setenv("CRATERKIT_LAMMPS", (folder.path() / "missing").c_str(), 1);
  std::string missing;
  try {
    (void)find_lammps();
  } catch (const std::runtime_error& e) {
    missing = e.what();
  }
  ::unsetenv("CRATERKIT_LAMMPS");
  EXPECT_NE(what.find("fake_lmp ended with exit status 3: not enough slots available"), std::string::npos)
      << what;
  EXPECT_NE(missing.find("CRATERKIT_LAMMPS=" + (folder.path() / "missing").string() +
                         ": not an executable program"),
            std::string::npos)
      << missing;
}

TEST(SettledBedKey, EveryDefiningValueChangesTheHashButTheProcessCountDoesNot) {
  const BedSpec base;
  const std::string hash = bed_hash(base);
  EXPECT_EQ(hash.size(), 16U);
  BedSpec other = base;
  other.processes = 2;
  EXPECT_EQ(bed_hash(other), hash);
  std::vector<BedSpec> changed(9, base);
  changed[0].depth *= 1.0 + 1e-15;
  changed[1].grain_sizes.max_diameter *= 1.1;
  changed[2].contact.rolling_friction += 0.01;
  changed[3].contact.restitution -= 0.1;
  changed[4].gravity = 1.4e-4;
  changed[5].seed = 2;
  changed[6].grain_density += 1;
  changed[7].length_y *= 2;
  changed[8].side_walls = true;
  for (const auto& spec : changed) EXPECT_NE(bed_hash(spec), hash) << bed_key(spec);
}

TEST(SettledBedKey, BedsTooSmallForTheirGrainsAreRefused) {
  BedSpec spec;
  spec.grain_sizes = {0.01, 0.012};
  spec.depth = 0.04;
  EXPECT_NE(input_error_of([&] {
              check_bed_spec(spec);
            }).find("bed.depth: value 0.04 m is under 4.2 largest grains"),
            std::string::npos);
  spec = BedSpec{};
  spec.grain_sizes = {0.02, 0.01};
  EXPECT_NE(
      input_error_of([&] { check_bed_spec(spec); }).find("bed.grain_sizes.max_diameter: value 0.01 is below"),
      std::string::npos);
}

TEST(SurfaceAndPacking, ACubicLatticeHasItsKnownPackingFractionAndTop) {
  // Simple cubic packing of equal spheres touching: pi/6 = 0.5236 of the volume.
  Grains grains;
  const double d = 0.01;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
      for (int k = 0; k < 6; ++k) grains.add((i + 0.5) * d, (j + 0.5) * d, (k + 0.5) * d, d, 2500);
  const Box box{0, 10 * d, 0, 10 * d, 0, 6 * d};
  EXPECT_NEAR(packing_fraction_between(grains, box, 0.0, 6 * d), std::numbers::pi / 6.0, 1e-12);
  // A slab through the grains' centres holds the same fraction; one through their tops the same.
  EXPECT_NEAR(packing_fraction_between(grains, box, 1.5 * d, 3.5 * d), std::numbers::pi / 6.0, 1e-12);
  EXPECT_NEAR(mean_surface_height(grains, box, d), 6 * d, 1e-15);
}

TEST(PileProfile, AHeapOfGrainsOnAKnownSlopeGivesThatAngle) {
  // A heap against x = 0: flat at 0.2 m up to x = 0.1 m, then a flank at 30 degrees down to the floor, built
  // of grains whose tops lie on that surface; the fit between 20 and 80 % of the height sees the flank only.
  Grains grains;
  const double d = 0.01;
  const double slope = std::tan(30.0 * std::numbers::pi / 180.0);
  for (int c = 0; c < 60; ++c) {
    const double x = (c + 0.5) * d;
    const double top = x < 0.1 ? 0.2 : std::max(0.0, 0.2 - slope * (x - 0.1));
    for (double z = 0.5 * d; z + 0.5 * d <= top + 1e-12; z += d) grains.add(x, 0.01, z, d, 2500);
    if (top > 0.5 * d) grains.add(x, 0.02, top - 0.5 * d, d, 2500);  // the exact top in each column
  }
  const SurfaceProfile profile = surface_profile(grains, 0.6, d);
  ASSERT_EQ(profile.x.size(), 60U);
  EXPECT_DOUBLE_EQ(profile.height[3], 0.2);
  const FlankFit fit = flank_slope(profile, 0.2, 0.8);
  EXPECT_NEAR(fit.angle_degrees, 30.0, 1e-9);
  EXPECT_EQ(fit.columns, 21);  // heights 0.04-0.16 m: 0.12 m / tan 30 / d columns, +-1
}

TEST(ReposeCalibration, ReadsTheTableAndInvertsItBetweenRows) {
  const test::ScratchDirectory folder("dem");
  const auto path = folder.path() / "calibration.csv";
  std::ofstream(path)
      << "# piles\nsliding_friction,rolling_friction,angle_degrees\n0.85,0.05,25\n0.85,0.1,30\n"
      << "0.85,0.3,36\n";
  const ReposeCalibration table = read_repose_calibration(path);
  EXPECT_EQ(table.sliding_friction, 0.85);
  EXPECT_NEAR(rolling_friction_for_repose_angle(table, 27.5), 0.075, 1e-15);
  EXPECT_NEAR(rolling_friction_for_repose_angle(table, 33.0), 0.2, 1e-15);
  EXPECT_EQ(rolling_friction_for_repose_angle(table, 25.0), 0.05);
  EXPECT_EQ(rolling_friction_for_repose_angle(table, 36.0), 0.3);
  EXPECT_EQ(
      input_error_of([&] { (void)rolling_friction_for_repose_angle(table, 40.0); }),
      "angle of repose 40 degrees: outside the calibrated piles' [25, 36] degrees (sliding friction 0.85)");
}

TEST(ReposeCalibration, ATableWithoutAUniqueInverseIsRefusedNamingItsLine) {
  const test::ScratchDirectory folder("dem");
  const auto path = folder.path() / "calibration.csv";
  std::ofstream(path) << "sliding_friction,rolling_friction,angle_degrees\n0.85,0.05,25\n0.85,0.1,24\n";
  try {
    (void)read_repose_calibration(path);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path.string() + ":3: angle_degrees 24 does not rise above 25"),
              std::string::npos)
        << e.what();
  }
  std::ofstream(path) << "sliding_friction,rolling_friction,angle_degrees\n0.85,0.05,25\n0.6,0.1,30\n";
  EXPECT_THROW((void)read_repose_calibration(path), std::runtime_error);
}

TEST(ReposeCalibration, TheShippedTableReads) {
  const ReposeCalibration table = shipped_repose_calibration();
  EXPECT_GE(table.rolling_friction.size(), 3U);
}

}  // namespace
}  // namespace craterkit::dem
