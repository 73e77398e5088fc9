// Snapshots and checkpoints: bit-for-bit round trip of every field, atomic writes, clear errors.
#include <hdf5.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <type_traits>

#include <gtest/gtest.h>

#include "craterkit/common/input_error.hpp"
#include "craterkit/sph/io/checkpoint.hpp"
#include "craterkit/sph/io/snapshot.hpp"
#include "craterkit/sph/io/solver_state.hpp"
#include "craterkit/sph/io/xdmf.hpp"
#include "sph_core/test_io_scratch_directory.hpp"

namespace sph = craterkit::sph;
namespace fs = std::filesystem;
using craterkit::test::ScratchDirectory;

namespace {

// Every field filled with random bit patterns (doubles: random finite values plus the awkward
// ones: -0, denormals, infinities, NaN, extremes), so that any conversion or truncation shows.
sph::Particles random_particles(std::size_t n, unsigned seed) {
  sph::Particles p;
  p.resize(n);
  std::mt19937_64 random(seed);
  p.for_each_field([&](std::string_view, auto& field) {
    using T = typename std::decay_t<decltype(field)>::value_type;
    for (auto& value : field) {
      const std::uint64_t bits = random();
      if constexpr (std::is_same_v<T, double>) {
        // Random sign, mantissa and exponent within finite doubles.
        const double mantissa = static_cast<double>(bits >> 11) * 0x1.0p-53;
        value = std::ldexp(mantissa, static_cast<int>(bits % 200) - 100) * ((bits & 1) ? -1 : 1);
      } else {
        value = static_cast<T>(bits);
      }
    }
    if constexpr (std::is_same_v<T, double>) {
      if (n >= 7) {
        field[0] = -0.0;
        field[1] = std::numeric_limits<double>::denorm_min();
        field[2] = std::numeric_limits<double>::infinity();
        field[3] = -std::numeric_limits<double>::infinity();
        field[4] = std::numeric_limits<double>::quiet_NaN();
        field[5] = std::numeric_limits<double>::max();
        field[6] = 0.1;
      }
    }
  });
  return p;
}

void expect_bitwise_equal(const sph::Particles& a, const sph::Particles& b) {
  ASSERT_EQ(a.size(), b.size());
  std::vector<std::string> names;
  a.for_each_field([&](std::string_view name, const auto&) { names.emplace_back(name); });
  std::size_t k = 0;
  a.for_each_field([&](std::string_view name, const auto& field_a) {
    std::size_t j = 0;
    b.for_each_field([&](std::string_view, const auto& field_b) {
      if (j++ != k) return;
      using A = std::decay_t<decltype(field_a)>;
      using B = std::decay_t<decltype(field_b)>;
      if constexpr (std::is_same_v<A, B>) {
        ASSERT_EQ(field_a.size(), field_b.size()) << name;
        EXPECT_EQ(0, std::memcmp(field_a.data(), field_b.data(), field_a.size() * sizeof(field_a[0])))
            << "field " << name << " differs";
      } else {
        ADD_FAILURE() << "field " << name << " changed type";
      }
    });
    ++k;
  });
}

sph::RunAttributes sample_attributes() {
  sph::RunAttributes attributes;
  attributes.time = 0.1 + 0.2;  // not representable in a short decimal: exact round trip needed
  attributes.step = 123456789012ULL;
  attributes.numbers["dt"] = 1.0 / 3.0;
  attributes.numbers["gravity_z"] = -1.5e-4;
  attributes.texts["config"] = "[run]\nend_time = 0.05 # \"quoted\"\n";
  attributes.texts["material"] = "basalt \xCE\xB1=5 (Benz & Asphaug 1999)";  // UTF-8 alpha
  return attributes;
}

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Names of the files in a directory (to show that no temporary file is left behind).
std::vector<std::string> directory_listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string dataset_units(const fs::path& h5, const char* dataset) {
  const hid_t file = H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t data = H5Dopen2(file, dataset, H5P_DEFAULT);
  const hid_t attribute = H5Aopen(data, "units", H5P_DEFAULT);
  const hid_t type = H5Aget_type(attribute);
  char* text = nullptr;
  H5Aread(attribute, type, &text);
  std::string units = text;
  H5free_memory(text);
  H5Tclose(type);
  H5Aclose(attribute);
  H5Dclose(data);
  H5Fclose(file);
  return units;
}

}  // namespace

TEST(IoSnapshot, RoundTripsEveryFieldBitForBit) {
  ScratchDirectory dir("snapshot_round_trip");
  const auto particles = random_particles(1000, 42);
  const auto attributes = sample_attributes();
  sph::write_snapshot(dir / "snap.h5", particles, attributes);

  sph::RunAttributes read_attributes;
  const auto read = sph::read_snapshot(dir / "snap.h5", &read_attributes);
  expect_bitwise_equal(particles, read);

  EXPECT_EQ(std::memcmp(&attributes.time, &read_attributes.time, sizeof(double)), 0);
  EXPECT_EQ(read_attributes.step, attributes.step);
  EXPECT_EQ(read_attributes.numbers, attributes.numbers);
  EXPECT_EQ(read_attributes.texts, attributes.texts);
  EXPECT_TRUE(fs::exists(dir / "snap.xdmf"));
  EXPECT_EQ(directory_listing(dir.path()), (std::vector<std::string>{"snap.h5", "snap.xdmf"}));
}

// Fluid runs drop the solid-mechanics group (96 bytes per particle): it is neither written nor
// expected on reading, and a file that holds it reads back with it.
TEST(IoSnapshot, SolidGroupIsWrittenOnlyWhenPresent) {
  ScratchDirectory dir("snapshot_fluid");
  auto fluid = random_particles(100, 7);
  fluid.set_solid_fields(false);
  EXPECT_TRUE(fluid.stress_xx.empty());
  EXPECT_EQ(fluid.stress_xx.capacity(), 0u);
  sph::write_snapshot(dir / "fluid.h5", fluid, {});
  const auto read = sph::read_snapshot(dir / "fluid.h5");
  EXPECT_FALSE(read.solid_fields);
  EXPECT_TRUE(read.stress_rate_yz.empty());
  expect_bitwise_equal(fluid, read);

  sph::write_checkpoint(dir / "solid.h5", random_particles(100, 8), {});
  const auto solid = sph::read_checkpoint(dir / "solid.h5");
  EXPECT_TRUE(solid.solid_fields);
  EXPECT_EQ(solid.total_strain.size(), 100u);

  // Re-allocating the group gives zeros for every particle.
  fluid.set_solid_fields(true);
  EXPECT_EQ(fluid.stress_yz.size(), 100u);
  EXPECT_EQ(fluid.stress_yz[99], 0.0);
}

TEST(IoSnapshot, DatasetsCarryTheirUnits) {
  ScratchDirectory dir("snapshot_units");
  sph::write_snapshot(dir / "snap.h5", random_particles(10, 1), {});
  EXPECT_EQ(dataset_units(dir / "snap.h5", "density"), "kg/m^3");
  EXPECT_EQ(dataset_units(dir / "snap.h5", "specific_energy"), "J/kg");
  EXPECT_EQ(dataset_units(dir / "snap.h5", "position"), "m");
  EXPECT_EQ(sph::field_unit("id"), "");
}

TEST(IoSnapshot, EveryPhysicalFieldHasAUnit) {
  // A field added to Particles must say its unit (identifiers, materials and flags have none).
  const sph::Particles particles;
  particles.for_each_field([](std::string_view name, const auto& field) {
    using Value = typename std::decay_t<decltype(field)>::value_type;
    if constexpr (std::is_floating_point_v<Value>) {
      EXPECT_FALSE(sph::field_unit(name).empty()) << name;
    }
  });
}

TEST(IoSnapshot, VisualisationVectorsInterleaveTheComponents) {
  ScratchDirectory dir("snapshot_vectors");
  const auto particles = random_particles(100, 3);
  sph::write_snapshot(dir / "snap.h5", particles, {});
  const hid_t file = H5Fopen((dir / "snap.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  for (const char* name : {"position", "velocity"}) {
    const hid_t data = H5Dopen2(file, name, H5P_DEFAULT);
    std::vector<double> values(300);
    ASSERT_GE(H5Dread(data, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
    H5Dclose(data);
    const bool position = std::string(name) == "position";
    for (std::size_t i = 0; i < 100; ++i) {
      const double a = position ? particles.x[i] : particles.vx[i];
      const double b = position ? particles.y[i] : particles.vy[i];
      const double c = position ? particles.z[i] : particles.vz[i];
      EXPECT_EQ(std::memcmp(&values[3 * i], &a, 8), 0) << name << " " << i;
      EXPECT_EQ(std::memcmp(&values[3 * i + 1], &b, 8), 0) << name << " " << i;
      EXPECT_EQ(std::memcmp(&values[3 * i + 2], &c, 8), 0) << name << " " << i;
    }
  }
  H5Fclose(file);
}

// The Cauchy stress sigma = S - P I for visualisation (XDMF Tensor6 order xx, xy, xz, yy, yz, zz), and
// deflate compression: the fields read back bit for bit.
TEST(IoSnapshot, StressTensorAndCompression) {
  ScratchDirectory dir("snapshot_stress");
  const auto particles = random_particles(200, 5);
  sph::write_snapshot(dir / "plain.h5", particles, {});
  sph::write_snapshot(dir / "packed.h5", particles, {}, 6);
  expect_bitwise_equal(particles, sph::read_snapshot(dir / "packed.h5"));
  const auto filters = [](const fs::path& path, const char* name) {
    const hid_t file = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    const hid_t data = H5Dopen2(file, name, H5P_DEFAULT);
    const hid_t plist = H5Dget_create_plist(data);
    const int n = H5Pget_nfilters(plist);
    H5Pclose(plist);
    H5Dclose(data);
    H5Fclose(file);
    return n;
  };
  EXPECT_EQ(filters(dir / "plain.h5", "density"), 0);
  EXPECT_EQ(filters(dir / "packed.h5", "density"), 1);
  EXPECT_EQ(filters(dir / "packed.h5", "stress"), 1);
  EXPECT_THROW(sph::write_snapshot(dir / "bad.h5", particles, {}, 10), std::invalid_argument);

  const hid_t file = H5Fopen((dir / "plain.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t data = H5Dopen2(file, "stress", H5P_DEFAULT);
  std::vector<double> sigma(6 * 200);
  ASSERT_GE(H5Dread(data, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, sigma.data()), 0);
  H5Dclose(data);
  H5Fclose(file);
  for (std::size_t i = 0; i < 200; i += 17) {
    const double p = particles.pressure[i];
    EXPECT_EQ(sigma[6 * i], particles.stress_xx[i] - p) << i;
    EXPECT_EQ(sigma[6 * i + 1], particles.stress_xy[i]) << i;
    EXPECT_EQ(sigma[6 * i + 4], particles.stress_yz[i]) << i;
    EXPECT_NEAR(sigma[6 * i] + sigma[6 * i + 3] + sigma[6 * i + 5], -3.0 * p, 1e-9 * (std::abs(p) + 1.0))
        << i;
  }
  // The sidecar shows it as a Tensor6 attribute.
  std::ifstream sidecar(dir / "plain.xdmf");
  const std::string xml((std::istreambuf_iterator<char>(sidecar)), std::istreambuf_iterator<char>());
  EXPECT_NE(xml.find("<Attribute Name=\"stress\" AttributeType=\"Tensor6\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("plain.h5:/stress"), std::string::npos);
}

TEST(IoCheckpoint, RoundTripsEveryFieldBitForBitWithoutSidecar) {
  ScratchDirectory dir("checkpoint_round_trip");
  const auto particles = random_particles(5000, 7);
  const auto attributes = sample_attributes();
  sph::write_checkpoint(dir / "checkpoint.h5", particles, attributes);
  EXPECT_EQ(directory_listing(dir.path()), (std::vector<std::string>{"checkpoint.h5"}));

  sph::RunAttributes read_attributes;
  expect_bitwise_equal(particles, sph::read_checkpoint(dir / "checkpoint.h5", &read_attributes));
  EXPECT_EQ(read_attributes.step, attributes.step);
  EXPECT_EQ(read_attributes.numbers, attributes.numbers);
  EXPECT_EQ(read_attributes.texts, attributes.texts);
  // A checkpoint is not a snapshot of the time series.
  EXPECT_THROW(sph::summarize_snapshot(dir / "checkpoint.h5"), craterkit::InputError);
}

TEST(IoCheckpoint, OverwritingReplacesTheWholeFile) {
  ScratchDirectory dir("checkpoint_overwrite");
  sph::write_checkpoint(dir / "c.h5", random_particles(3000, 1), {});
  const auto second = random_particles(10, 2);
  sph::write_checkpoint(dir / "c.h5", second, {});
  expect_bitwise_equal(second, sph::read_checkpoint(dir / "c.h5"));
}

TEST(IoSnapshot, SameStateGivesTheSameBytes) {
  // No modification times are stored, so a resumed run's files can be compared with cmp. HDF5
  // would record times with one-second resolution: write across a second boundary.
  ScratchDirectory dir("snapshot_reproducible");
  const auto particles = random_particles(100, 9);
  sph::write_snapshot(dir / "a.h5", particles, sample_attributes());
  sph::write_checkpoint(dir / "c.h5", particles, sample_attributes());
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  sph::write_snapshot(dir / "b.h5", particles, sample_attributes());
  sph::write_checkpoint(dir / "d.h5", particles, sample_attributes());
  EXPECT_EQ(file_bytes(dir / "a.h5"), file_bytes(dir / "b.h5"));
  EXPECT_EQ(file_bytes(dir / "c.h5"), file_bytes(dir / "d.h5"));
}

TEST(IoSnapshot, EmptyParticleSetRoundTrips) {
  ScratchDirectory dir("snapshot_empty");
  sph::write_snapshot(dir / "empty.h5", sph::Particles{}, {});
  EXPECT_EQ(sph::read_snapshot(dir / "empty.h5").size(), 0u);
}

TEST(IoSnapshot, FailedWriteLeavesNoFileAndKeepsThePreviousOne) {
  ScratchDirectory dir("snapshot_atomic");
  const auto good = random_particles(200, 11);
  sph::write_snapshot(dir / "snap.h5", good, {});
  const std::string before_h5 = file_bytes(dir / "snap.h5");
  const std::string before_xdmf = file_bytes(dir / "snap.xdmf");

  // A field shorter than the others is detected while the file is being written (after the
  // attributes and the first datasets are in the temporary file).
  auto broken = random_particles(300, 12);
  broken.pressure.pop_back();
  EXPECT_THROW(sph::write_snapshot(dir / "snap.h5", broken, {}), std::invalid_argument);
  EXPECT_THROW(sph::write_checkpoint(dir / "other.h5", broken, {}), std::invalid_argument);

  EXPECT_EQ(file_bytes(dir / "snap.h5"), before_h5);
  EXPECT_EQ(file_bytes(dir / "snap.xdmf"), before_xdmf);
  EXPECT_EQ(directory_listing(dir.path()), (std::vector<std::string>{"snap.h5", "snap.xdmf"}));
  expect_bitwise_equal(good, sph::read_snapshot(dir / "snap.h5"));
}

TEST(IoSnapshot, ReservedAttributeNamesAreRejectedBeforeWriting) {
  ScratchDirectory dir("snapshot_reserved");
  sph::RunAttributes attributes;
  attributes.numbers["time"] = 1;
  EXPECT_THROW(sph::write_snapshot(dir / "s.h5", random_particles(5, 1), attributes), std::invalid_argument);
  sph::RunAttributes both;
  both.numbers["a"] = 1;
  both.texts["a"] = "x";
  EXPECT_THROW(sph::write_checkpoint(dir / "c.h5", random_particles(5, 1), both), std::invalid_argument);
  EXPECT_TRUE(directory_listing(dir.path()).empty());
}

TEST(IoSnapshot, UnwritableDirectoryThrowsAndCreatesNothing) {
  ScratchDirectory dir("snapshot_no_dir");
  EXPECT_THROW(sph::write_snapshot(dir / "missing" / "s.h5", random_particles(5, 1), {}), std::runtime_error);
  EXPECT_TRUE(directory_listing(dir.path()).empty());
}

// ---- errors on reading --------------------------------------------------------------------------

namespace {

// Runs read_checkpoint and returns the InputError message ("" if none was thrown).
std::string read_error(const fs::path& path) {
  try {
    sph::read_checkpoint(path);
  } catch (const craterkit::InputError& error) {
    return error.what();
  }
  return "";
}

}  // namespace

TEST(IoCheckpoint, MissingFileIsAClearInputError) {
  ScratchDirectory dir("checkpoint_missing");
  const auto message = read_error(dir / "nothing.h5");
  EXPECT_NE(message.find("nothing.h5"), std::string::npos) << message;
  EXPECT_NE(message.find("no such file"), std::string::npos) << message;
}

TEST(IoCheckpoint, NonHdf5FileIsAClearInputError) {
  ScratchDirectory dir("checkpoint_text");
  std::ofstream(dir / "text.h5") << "time,step\n0,0\n";
  const auto message = read_error(dir / "text.h5");
  EXPECT_NE(message.find("not an HDF5 file"), std::string::npos) << message;
}

TEST(IoCheckpoint, TruncatedFileIsAClearInputError) {
  ScratchDirectory dir("checkpoint_truncated");
  sph::write_checkpoint(dir / "full.h5", random_particles(2000, 5), {});
  const std::string bytes = file_bytes(dir / "full.h5");
  for (const double fraction : {0.5, 0.99}) {
    std::ofstream(dir / "cut.h5", std::ios::binary | std::ios::trunc)
        .write(bytes.data(), static_cast<std::streamsize>(bytes.size() * fraction));
    const auto message = read_error(dir / "cut.h5");
    EXPECT_NE(message.find("cut.h5"), std::string::npos) << fraction << ": " << message;
  }
}

TEST(IoCheckpoint, ForeignHdf5FileIsAClearInputError) {
  ScratchDirectory dir("checkpoint_foreign");
  const hid_t file = H5Fcreate((dir / "foreign.h5").c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  H5Fclose(file);
  const auto message = read_error(dir / "foreign.h5");
  EXPECT_NE(message.find("not a craterkit particle file"), std::string::npos) << message;
}

TEST(IoCheckpoint, MissingOrMistypedFieldIsNamed) {
  ScratchDirectory dir("checkpoint_fields");
  sph::write_checkpoint(dir / "c.h5", random_particles(50, 5), {});

  hid_t file = H5Fopen((dir / "c.h5").c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(H5Ldelete(file, "distention", H5P_DEFAULT), 0);
  H5Fclose(file);
  // Changed by another program: refused as damaged until its integrity record is written anew.
  auto message = read_error(dir / "c.h5");
  EXPECT_NE(message.find("checksum does not match"), std::string::npos) << message;
  sph::reseal_particle_file(dir / "c.h5");
  message = read_error(dir / "c.h5");
  EXPECT_NE(message.find("'distention' is missing"), std::string::npos) << message;

  // Replace 'density' by 32-bit floats: reading it as doubles would lose the exact state.
  sph::write_checkpoint(dir / "c.h5", random_particles(50, 5), {});
  file = H5Fopen((dir / "c.h5").c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(H5Ldelete(file, "density", H5P_DEFAULT), 0);
  const hsize_t n = 50;
  const hid_t space = H5Screate_simple(1, &n, nullptr);
  const hid_t data =
      H5Dcreate2(file, "density", H5T_IEEE_F32LE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dclose(data);
  H5Sclose(space);
  H5Fclose(file);
  sph::reseal_particle_file(dir / "c.h5");
  message = read_error(dir / "c.h5");
  EXPECT_NE(message.find("'density' does not hold 64-bit floats"), std::string::npos) << message;

  // A dataset of the wrong length.
  sph::write_checkpoint(dir / "c.h5", random_particles(50, 5), {});
  file = H5Fopen((dir / "c.h5").c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(H5Ldelete(file, "vz", H5P_DEFAULT), 0);
  const hsize_t short_n = 49;
  const hid_t short_space = H5Screate_simple(1, &short_n, nullptr);
  const hid_t short_data =
      H5Dcreate2(file, "vz", H5T_IEEE_F64LE, short_space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Dclose(short_data);
  H5Sclose(short_space);
  H5Fclose(file);
  sph::reseal_particle_file(dir / "c.h5");
  message = read_error(dir / "c.h5");
  EXPECT_NE(message.find("'vz' has 49 entries, particle_count is 50"), std::string::npos) << message;
}

// The solver's state survives the attributes of a checkpoint exactly, and the late stage's entries appear
// only after the switch.
TEST(SolverStateAttributes, RoundTripBeforeAndAfterTheSwitch) {
  craterkit::sph::SolverState state;
  state.time = 0.125;
  state.step = 77;
  state.next_time_step = 1.0 / 3.0;
  state.initial.mass = 2.5;
  state.initial.momentum_z = -1e-17;
  state.initial.total_energy = 6.02e23;
  state.initial.absolute_momentum = 0.1;
  craterkit::sph::RunAttributes before;
  craterkit::sph::write_solver_state(state, before);
  EXPECT_EQ(before.numbers.count("late_stage_transition_time"), 0u);
  EXPECT_EQ(before.texts.count("late_stage"), 0u);
  const auto read = craterkit::sph::read_solver_state(before, "test");
  EXPECT_EQ(read.time, state.time);
  EXPECT_EQ(read.step, state.step);
  EXPECT_EQ(read.next_time_step, state.next_time_step);
  EXPECT_EQ(read.initial.mass, state.initial.mass);
  EXPECT_EQ(read.initial.momentum_z, state.initial.momentum_z);
  EXPECT_EQ(read.initial.total_energy, state.initial.total_energy);
  EXPECT_EQ(read.initial.absolute_momentum, state.initial.absolute_momentum);
  EXPECT_FALSE(read.late_stage_active);

  state.late_stage_active = true;
  state.transition_time = 0.1;
  state.A_low = 0.027e6;
  state.mach_at_transition = 0.02;
  state.late_stage_max_mach = 0.05;
  craterkit::sph::RunAttributes after;
  craterkit::sph::write_solver_state(state, after);
  EXPECT_EQ(after.numbers.at("late_stage_transition_time"), 0.1);
  EXPECT_EQ(after.numbers.at("late_stage_A_low"), 0.027e6);
  EXPECT_NE(after.texts.at("late_stage").find("A_low"), std::string::npos);
  const auto late = craterkit::sph::read_solver_state(after, "test");
  EXPECT_TRUE(late.late_stage_active);
  EXPECT_EQ(late.mach_at_transition, 0.02);
  EXPECT_EQ(late.late_stage_max_mach, 0.05);

  after.numbers.erase("next_time_step");
  try {
    (void)craterkit::sph::read_solver_state(after, "run/checkpoint.h5");
    FAIL() << "a missing attribute was accepted";
  } catch (const craterkit::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("run/checkpoint.h5: attribute next_time_step missing"),
              std::string::npos)
        << e.what();
  }
}
