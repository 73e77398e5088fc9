#pragma once
// Helpers of the study tests: a scratch folder per test, files written into it, and the tiny impact base of
// tests/apps/test_simulate_cli.sh (a resolved 5450 kg projectile of the target's density at 50 m/s into a
// 5 m hemisphere at dx = 0.5 m under g = 1 m/s^2; quarter domain).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "craterkit/common/input_error.hpp"

namespace craterkit::study::test {

namespace fs = std::filesystem;

class Scratch {
 public:
  Scratch() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("craterkit_study_" + std::string(info->test_suite_name()) + "_" +
                                         info->name() + "_" + std::to_string(::getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~Scratch() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  [[nodiscard]] const fs::path& path() const { return path_; }
  fs::path write(const std::string& name, const std::string& text) const {
    const auto file = path_ / name;
    fs::create_directories(file.parent_path());
    std::ofstream(file, std::ios::binary) << text;
    return file;
  }

 private:
  fs::path path_;
};

inline std::string read(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

inline const char* tiny_base() {
  return R"([problem]
name = "tiny-impact"
setup = "impact"
[impact]
projectile_model = "resolved"
projectile_density = 1300.0
projectile_mass = 5450.0
impact_speed = 50.0
A_low = 0.27e6
domain_radius = 5.0
particle_spacing = 0.5
t_transition = 0.01
escape_speed = 1.0
symmetry = "quarter"
[run]
end_time = 0.3
gravity = [0.0, 0.0, -1.0]
[kernel]
max_smoothing_length = 1.8
[crater]
check_interval = 0.05
)";
}

// The message of the InputError that `f` throws ("" and a test failure when it throws none).
template <class F>
std::string input_error(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError";
  return "";
}

}  // namespace craterkit::study::test
