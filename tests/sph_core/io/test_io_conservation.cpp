// Conserved quantities against hand sums, thread-count independence, and the CSV log (exact
// numbers, truncation on resume so that a resumed log equals an uninterrupted one).
#include <omp.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "craterkit/common/input_error.hpp"
#include "craterkit/sph/io/conservation_log.hpp"
#include "sph_core/test_io_scratch_directory.hpp"

namespace sph = craterkit::sph;
namespace fs = std::filesystem;
using craterkit::test::ScratchDirectory;

namespace {

// Three particles whose sums are worked out by hand below; one fixed and one ejected, both counted.
sph::Particles three_particles() {
  sph::Particles p;
  p.resize(3);
  const double m[3] = {1, 2, 3};
  const double v[3][3] = {{1, 0, 0}, {0, -2, 0}, {1, 1, 1}};
  const double x[3][3] = {{0, 0, 1}, {5, -3, 2}, {1, 1, -1}};
  const double u[3] = {10, 20, 30};
  for (int i = 0; i < 3; ++i) {
    p.mass[i] = m[i];
    p.vx[i] = v[i][0];
    p.vy[i] = v[i][1];
    p.vz[i] = v[i][2];
    p.x[i] = x[i][0];
    p.y[i] = x[i][1];
    p.z[i] = x[i][2];
    p.specific_energy[i] = u[i];
  }
  p.flags[1] = sph::particle_fixed;
  p.flags[2] = sph::particle_ejected;
  return p;
}

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

sph::ConservedQuantities row(std::uint64_t step) {
  sph::ConservedQuantities q;
  q.step = step;
  q.time = 1e-3 * static_cast<double>(step) / 3.0;
  q.mass = 1.0 / 7.0;
  q.momentum_x = -1e-300 * static_cast<double>(step);
  q.momentum_y = 0.1 * static_cast<double>(step);
  q.momentum_z = std::nextafter(1.0, 2.0);
  q.kinetic_energy = 2.0 / 3.0;
  q.internal_energy = 1e20 / 3.0;
  q.potential_energy = -5e-5;
  q.total_energy = q.kinetic_energy + q.internal_energy + q.potential_energy;
  q.absolute_momentum = 12345.678901234567;
  return q;
}

}  // namespace

TEST(IoConservation, MatchesHandSums) {
  // gravity g = (0.5, 0, -2) m/s^2. By hand:
  //   mass = 1 + 2 + 3 = 6
  //   p = (1*1 + 0 + 3*1, 0 + 2*(-2) + 3*1, 0 + 0 + 3*1) = (4, -1, 3)
  //   K = 1/2 (1*1 + 2*4 + 3*3) = 9
  //   U = 1*10 + 2*20 + 3*30 = 140
  //   P = -sum m g.x = -sum m (0.5 x - 2 z) = -(0.5*(0 + 10 + 3) - 2*(1 + 4 - 3)) = -(6.5 - 4) = -2.5
  //   E = 9 + 140 - 2.5 = 146.5;  sum m|v| = 1 + 2*2 + 3*sqrt(3)
  const auto q = sph::measure_conserved(three_particles(), {0.5, 0, -2});
  EXPECT_DOUBLE_EQ(q.mass, 6);
  EXPECT_DOUBLE_EQ(q.momentum_x, 4);
  EXPECT_DOUBLE_EQ(q.momentum_y, -1);
  EXPECT_DOUBLE_EQ(q.momentum_z, 3);
  EXPECT_DOUBLE_EQ(q.kinetic_energy, 9);
  EXPECT_DOUBLE_EQ(q.internal_energy, 140);
  EXPECT_DOUBLE_EQ(q.potential_energy, -2.5);
  EXPECT_DOUBLE_EQ(q.total_energy, 146.5);
  EXPECT_DOUBLE_EQ(q.absolute_momentum, 5 + 3 * std::sqrt(3.0));
  EXPECT_EQ(q.time, 0);
  EXPECT_EQ(q.step, 0u);
}

TEST(IoConservation, EmptySetIsZero) {
  const auto q = sph::measure_conserved(sph::Particles{}, {0, 0, -1});
  EXPECT_EQ(q.mass, 0);
  EXPECT_EQ(q.total_energy, 0);
}

TEST(IoConservation, IndependentOfThreadCountBitForBit) {
  sph::Particles p;
  const std::size_t n = 200003;  // not a multiple of the block size
  p.resize(n);
  std::mt19937_64 random(5);
  std::uniform_real_distribution<double> uniform(-1, 1);
  for (std::size_t i = 0; i < n; ++i) {
    p.mass[i] = 1 + uniform(random);
    p.vx[i] = 1e3 * uniform(random);
    p.vy[i] = uniform(random);
    p.vz[i] = 1e-3 * uniform(random);
    p.x[i] = uniform(random);
    p.y[i] = uniform(random);
    p.z[i] = uniform(random);
    p.specific_energy[i] = 1e6 * (1 + uniform(random));
  }
  const int threads_before = omp_get_max_threads();
  omp_set_num_threads(1);
  const auto one = sph::measure_conserved(p, {0, 0, -9.81});
  omp_set_num_threads(2);
  const auto two = sph::measure_conserved(p, {0, 0, -9.81});
  omp_set_num_threads(threads_before);
  EXPECT_EQ(std::memcmp(&one, &two, sizeof one), 0);

  // And the compensated sums agree with a long-double reference to a few ulps.
  long double px = 0, energy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    px += static_cast<long double>(p.mass[i]) * p.vx[i];
    energy += static_cast<long double>(p.mass[i]) * p.specific_energy[i];
  }
  EXPECT_NEAR(one.momentum_x, static_cast<double>(px), 1e-15 * one.absolute_momentum);
  EXPECT_NEAR(one.internal_energy, static_cast<double>(energy), 4e-16 * one.internal_energy);
}

TEST(IoConservation, RelativeErrors) {
  sph::ConservedQuantities initial;
  initial.total_energy = 2;
  initial.absolute_momentum = 10;
  sph::ConservedQuantities now = initial;
  now.total_energy = 2.001;
  now.momentum_x = 0.3;
  now.momentum_y = 0.4;  // |dp| = 0.5
  now.absolute_momentum = 20;
  EXPECT_NEAR(sph::relative_energy_error(initial, now), 5e-4, 1e-15);
  EXPECT_DOUBLE_EQ(sph::relative_momentum_error(initial, now), 0.5 / 20);

  // Zero total energy: scaled by the sum of the magnitudes of its parts.
  sph::ConservedQuantities balanced;
  balanced.kinetic_energy = 3;
  balanced.potential_energy = -3;
  sph::ConservedQuantities later = balanced;
  later.total_energy = 0.06;
  EXPECT_DOUBLE_EQ(sph::relative_energy_error(balanced, later), 0.01);
  EXPECT_EQ(sph::relative_momentum_error(sph::ConservedQuantities{}, sph::ConservedQuantities{}), 0);
}

TEST(IoConservationLog, RowsRoundTripExactly) {
  ScratchDirectory dir("log_round_trip");
  {
    sph::ConservationLog log(dir / "conservation.csv");
    log.append(row(3));
  }
  std::ifstream in(dir / "conservation.csv");
  std::string header, line;
  std::getline(in, header);
  std::getline(in, line);
  EXPECT_EQ(header, sph::ConservationLog::header());
  std::vector<double> values;
  std::stringstream columns(line);
  for (std::string column; std::getline(columns, column, ',');)
    values.push_back(std::strtod(column.c_str(), nullptr));
  const auto q = row(3);
  const std::vector<double> expected{q.time,
                                     3,
                                     q.mass,
                                     q.momentum_x,
                                     q.momentum_y,
                                     q.momentum_z,
                                     q.kinetic_energy,
                                     q.internal_energy,
                                     q.potential_energy,
                                     q.total_energy,
                                     q.absolute_momentum};
  ASSERT_EQ(values.size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) EXPECT_EQ(values[k], expected[k]) << "column " << k;
}

TEST(IoConservationLog, ResumedLogEqualsUninterruptedLog) {
  ScratchDirectory dir("log_resume");
  {
    sph::ConservationLog log(dir / "uninterrupted.csv");
    for (std::uint64_t step = 0; step <= 10; ++step) log.append(row(step));
  }
  // The interrupted run wrote steps 0..8, was killed while writing step 9, and restarts from its
  // checkpoint at step 6.
  {
    sph::ConservationLog log(dir / "resumed.csv");
    for (std::uint64_t step = 0; step <= 8; ++step) log.append(row(step));
  }
  {
    std::ofstream partial(dir / "resumed.csv", std::ios::binary | std::ios::app);
    partial << "3.0000000000000001e-06,9,0.142857";
  }
  {
    sph::ConservationLog log(dir / "resumed.csv", 6);
    for (std::uint64_t step = 7; step <= 10; ++step) log.append(row(step));
  }
  EXPECT_EQ(file_bytes(dir / "resumed.csv"), file_bytes(dir / "uninterrupted.csv"));
}

TEST(IoConservationLog, ResumeWithoutLogStartsANewOne) {
  ScratchDirectory dir("log_resume_missing");
  {
    sph::ConservationLog log(dir / "c.csv", 5);
    log.append(row(6));
  }
  std::ifstream in(dir / "c.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, sph::ConservationLog::header());
}

TEST(IoConservationLog, ResumeRejectsForeignOrMalformedLogs) {
  ScratchDirectory dir("log_resume_bad");
  std::ofstream(dir / "foreign.csv") << "time,energy\n0,1\n";
  EXPECT_THROW(sph::ConservationLog(dir / "foreign.csv", 3), craterkit::InputError);
  EXPECT_EQ(file_bytes(dir / "foreign.csv"), "time,energy\n0,1\n");  // left alone

  std::ofstream(dir / "bad.csv") << sph::ConservationLog::header() << "\n0,0,1,0,0,0,0,0,0,0,0\n0.1,x,1\n";
  try {
    sph::ConservationLog log(dir / "bad.csv", 3);
    ADD_FAILURE() << "no error";
  } catch (const craterkit::InputError& error) {
    EXPECT_NE(std::string(error.what()).find("row 3"), std::string::npos) << error.what();
  }
}
