// Integrity of particle files and resumable logs: a damaged checkpoint is an error naming the file, never a
// silently different state; a resumed log that lost rows or is missing is an error, never a new start.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "craterkit/common/input_error.hpp"
#include "craterkit/sph/io/checkpoint.hpp"
#include "craterkit/sph/io/step_csv_log.hpp"
#include "sph_core/test_io_scratch_directory.hpp"

namespace sph = craterkit::sph;
namespace fs = std::filesystem;
using craterkit::test::ScratchDirectory;

namespace {

sph::Particles sample_particles(std::size_t n) {
  sph::Particles p;
  p.solid_fields = true;
  p.resize(n);
  std::mt19937_64 random(7);
  p.for_each_field([&](std::string_view, auto& field) {
    using T = typename std::decay_t<decltype(field)>::value_type;
    for (auto& value : field) {
      if constexpr (std::is_floating_point_v<T>)
        value = static_cast<T>(static_cast<double>(random() % 100000) * 1e-3);
      else
        value = static_cast<T>(random() % 100);
    }
  });
  return p;
}

// Same fields bit for bit.
bool same_particles(const sph::Particles& a, const sph::Particles& b) {
  if (a.size() != b.size() || a.solid_fields != b.solid_fields) return false;
  std::vector<std::string> a_bytes, b_bytes;
  a.for_each_field([&](std::string_view, const auto& f) {
    a_bytes.emplace_back(reinterpret_cast<const char*>(f.data()), f.size() * sizeof(f[0]));
  });
  b.for_each_field([&](std::string_view, const auto& f) {
    b_bytes.emplace_back(reinterpret_cast<const char*>(f.data()), f.size() * sizeof(f[0]));
  });
  return a_bytes == b_bytes;
}

bool same_attributes(const sph::RunAttributes& a, const sph::RunAttributes& b) {
  auto bits = [](double x) {
    std::uint64_t u = 0;
    std::memcpy(&u, &x, sizeof u);
    return u;
  };
  if (bits(a.time) != bits(b.time) || a.step != b.step || a.texts != b.texts) return false;
  if (a.numbers.size() != b.numbers.size()) return false;
  for (const auto& [k, v] : a.numbers) {
    if (b.numbers.count(k) == 0 || bits(b.numbers.at(k)) != bits(v)) return false;
  }
  return true;
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace

// Bytes all over a checkpoint damaged in turn (every 53rd byte, a different pattern each time): reading it
// either fails with an InputError that names the file, or gives back exactly what was written (a byte the
// reader never uses: padding, free space). Without checksums most damaged data bytes read back as other
// particles.
TEST(ParticleFileIntegrity, ADamagedCheckpointIsAnErrorNamingTheFileOrReadsBackExactly) {
  const ScratchDirectory dir("integrity");
  const auto path = dir / "checkpoint.h5";
  const sph::Particles particles = sample_particles(100);
  sph::RunAttributes attributes;
  attributes.time = 0.125;
  attributes.step = 42;
  attributes.numbers["dt"] = 1e-4;
  attributes.texts["setup"] = "impact";
  sph::write_checkpoint(path, particles, attributes);
  const std::string good = read_bytes(path);
  ASSERT_GT(good.size(), 5000u);

  std::size_t errors = 0, unchanged = 0;
  for (std::size_t offset = 0; offset < good.size(); offset += 53) {
    std::string bad = good;
    bad[offset] = static_cast<char>(bad[offset] ^ (1 + offset % 255));
    write_bytes(path, bad);
    try {
      sph::RunAttributes read_attributes;
      const sph::Particles read = sph::read_checkpoint(path, &read_attributes);
      ASSERT_TRUE(same_particles(read, particles) && same_attributes(read_attributes, attributes))
          << "byte " << offset << " of " << good.size() << " damaged: read back without error, but different";
      ++unchanged;
    } catch (const craterkit::InputError& e) {
      ASSERT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
      ++errors;
    }
  }
  std::printf("%zu damaged bytes: %zu errors, %zu read back unchanged\n", errors + unchanged, errors,
              unchanged);
  EXPECT_GT(errors, 9 * unchanged);  // nearly every byte of the file matters
}

TEST(ParticleFileIntegrity, ATruncatedCheckpointIsAnErrorNamingTheFile) {
  const ScratchDirectory dir("integrity_truncated");
  const auto path = dir / "checkpoint.h5";
  sph::write_checkpoint(path, sample_particles(200), {});
  const std::string good = read_bytes(path);
  for (const double fraction : {0.0, 0.1, 0.5, 0.9, 0.999}) {
    write_bytes(path, good.substr(0, static_cast<std::size_t>(fraction * static_cast<double>(good.size()))));
    try {
      (void)sph::read_checkpoint(path);
      ADD_FAILURE() << "a checkpoint cut to " << fraction << " of its length was read";
    } catch (const craterkit::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
  }
}

// A resumed log checks that it still holds the rows the checkpoint counted.
TEST(StepCsvLogResume, AMissingOrTruncatedLogIsAnErrorNamingTheFile) {
  const ScratchDirectory dir("log_resume");
  const auto csv = dir / "growth.csv";
  {
    sph::StepCsvLog log(csv, "time,step,value", 1);
    for (int step = 0; step <= 40; step += 10) log.append("0.5," + std::to_string(step) + ",1");
    EXPECT_EQ(log.rows(), 5u);
  }
  const std::string whole = read_bytes(csv);
  {
    const sph::StepCsvLog resumed(csv, "time,step,value", 1, 30, 4);
    EXPECT_EQ(resumed.rows(), 4u);  // rows of steps 0 to 30
  }
  write_bytes(csv, whole);
  // Cut after the row of step 10: two rows up to step 30 where the checkpoint counted four.
  write_bytes(csv, whole.substr(0, whole.find("0.5,20")));
  try {
    const sph::StepCsvLog resumed(csv, "time,step,value", 1, 30, 4);
    ADD_FAILURE() << "a truncated log was resumed";
  } catch (const craterkit::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(csv.string()), std::string::npos) << what;
    EXPECT_NE(what.find("holds 2 rows"), std::string::npos) << what;
    EXPECT_NE(what.find("held 4"), std::string::npos) << what;
  }
  fs::remove(csv);
  try {
    const sph::StepCsvLog resumed(csv, "time,step,value", 1, 30, 4);
    ADD_FAILURE() << "a missing log was started anew";
  } catch (const craterkit::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(csv.string() + ": missing"), std::string::npos) << e.what();
  }
  // Without an expected count (a checkpoint of an older version) a missing log starts anew, as before.
  const sph::StepCsvLog fresh(csv, "time,step,value", 1, 30);
  EXPECT_EQ(fresh.rows(), 0u);
}
