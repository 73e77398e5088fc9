// Mirror boundaries in the engine: a small vertical impact (resolved projectile) run on the full domain and
// on the quarter with mirror planes x = 0 and y = 0 (impact.symmetry = "quarter") agree particle by
// particle; a quarter run resumed from a checkpoint ends bitwise where an uninterrupted one ends, and it
// does not depend on the thread count.
#include <gtest/gtest.h>
#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <vector>

#include "craterkit/impact/impact_run.hpp"
#include "craterkit/sph/io/checkpoint.hpp"
#include "impact/impact_test_helpers.hpp"
#include "sph_core/engine_test_helpers.hpp"

using namespace craterkit::sph;
using namespace craterkit::impact;
namespace fs = std::filesystem;

namespace {

// The tiny impact of test_impact_run.cpp (resolved projectile of the target's density, 50 m/s, R_dom = 5 m,
// dx = 0.5 m, g = 1 m/s^2: 2,144 particles full, 536 in the quarter), with a 10 % skin so that the lists
// are kept over several steps (needs_rebuild() with images) and a curve sort every 7 steps.
ImpactConfig small_impact(DomainSymmetry symmetry) {
  ImpactConfig config;
  config.simulation = SimulationConfig{};  // generic solver defaults: the test sets the impact ones it uses
  ImpactSetup s;
  s.projectile_model = ProjectileModel::resolved;
  s.projectile_density = 1300.0;
  s.projectile_mass = 5450.0;  // a = 1.0 m = 2 dx
  s.impact_speed = 50.0;
  s.low_sound_speed_modulus = 0.27e6;
  s.domain_radius = 5.0;
  s.particle_spacing = 0.5;
  s.transition_time = 0.01;
  s.symmetry = symmetry;
  config.impact = s;
  config.simulation.name = "mirror-impact";
  config.simulation.run.end_time = 1.0;
  config.simulation.solver.gravity = {0.0, 0.0, -1.0};
  config.simulation.solver.time_step.velocity_change = 0.1;
  config.simulation.solver.time_step.energy_floor = s.impact_speed * s.impact_speed / 400.0;
  config.simulation.solver.smoothing.max_smoothing_length =
      3.0 * config.simulation.solver.smoothing.eta * s.particle_spacing;
  config.simulation.solver.neighbours.search.skin = 0.1;
  config.simulation.solver.neighbours.sort_interval = 7;
  config.crater.check_interval = 0.1;
  config.simulation.output.checkpoint_interval_seconds = 0;
  return config;
}

fs::path scratch(const std::string& name) {
  const auto dir =
      fs::temp_directory_path() / ("craterkit_mirror_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

using Position = std::tuple<double, double, double>;

// Sign of a field under the reflection (x, y) -> (sx x, sy y): polar vectors flip their reflected
// components, S_xy (and its rate) goes with sx sy, S_xz with sx, S_yz with sy; scalars keep theirs.
double reflection_sign(std::string_view name, double sx, double sy) {
  const auto ends = [&](std::string_view suffix) {
    return name.size() >= suffix.size() && name.substr(name.size() - suffix.size()) == suffix;
  };
  if (name == "x" || name == "vx" || name == "acceleration_x") return sx;
  if (name == "y" || name == "vy" || name == "acceleration_y") return sy;
  if (ends("_xy")) return sx * sy;
  if (ends("_xz")) return sx;
  if (ends("_yz")) return sy;
  return 1.0;
}

// Per double field: the largest |quarter - full counterpart| and the largest asymmetry of the full run
// itself (|reflected partner - counterpart| over the three mirror partners), both relative to the
// field's largest magnitude in the full run.
struct FieldDifference {
  std::string name;
  double quarter_vs_full = 0.0;
  double full_asymmetry = 0.0;
};

class FullAndQuarter {
 public:
  FullAndQuarter()
      : full_(small_impact(DomainSymmetry::full).simulation.solver,
              build_impact_run(small_impact(DomainSymmetry::full)).problem),
        quarter_(small_impact(DomainSymmetry::quarter).simulation.solver,
                 build_impact_run(small_impact(DomainSymmetry::quarter)).problem) {
    // Quarter id -> ids of the full-run particles at (sx x, sy y, z), by the initial positions (the
    // quarter's lattice is exactly that of the full domain: nodes at (i + 1/2) dx).
    std::map<Position, std::uint64_t> full_ids;
    const Particles& f = full_.particles();
    for (std::size_t i = 0; i < f.size(); ++i) full_ids[{f.x[i], f.y[i], f.z[i]}] = f.id[i];
    const Particles& q = quarter_.particles();
    EXPECT_EQ(4 * q.size(), f.size());
    for (std::size_t i = 0; i < q.size(); ++i) {
      initial_[q.id[i]] = {q.x[i], q.y[i], q.z[i]};
      for (int s = 0; s < 4; ++s) {
        const auto it = full_ids.find({(s & 1) ? -q.x[i] : q.x[i], (s & 2) ? -q.y[i] : q.y[i], q.z[i]});
        if (it == full_ids.end())
          throw std::runtime_error("quarter particle without a full-domain counterpart");
        partners_[q.id[i]][s] = it->second;
      }
    }
  }

  void step(double target) {
    full_.step(target);
    quarter_.step(target);
  }
  Simulation& full() { return full_; }
  Simulation& quarter() { return quarter_; }

  [[nodiscard]] std::vector<FieldDifference> differences() const {
    const Particles& f = full_.particles();
    const Particles& q = quarter_.particles();
    std::map<std::uint64_t, std::size_t> full_index;
    for (std::size_t i = 0; i < f.size(); ++i) full_index[f.id[i]] = i;
    std::vector<FieldDifference> out;
    q.for_each_field([&](std::string_view name, const auto& field) {
      f.for_each_field([&](std::string_view other, const auto& full_field) {
        using T = typename std::decay_t<decltype(field)>::value_type;
        using U = typename std::decay_t<decltype(full_field)>::value_type;
        if constexpr (std::is_same_v<T, U>) {
          if (name != other || name == "id") return;
          FieldDifference d{std::string(name)};
          double scale = 0.0;
          for (const auto v : full_field) scale = std::max(scale, std::abs(double(v)));
          if (scale == 0.0) scale = 1.0;
          for (std::size_t i = 0; i < q.size(); ++i) {
            const auto& ids = partners_.at(q.id[i]);
            const double own = double(full_field[full_index.at(ids[0])]);
            d.quarter_vs_full = std::max(d.quarter_vs_full, std::abs(double(field[i]) - own) / scale);
            for (int s = 1; s < 4; ++s) {
              const double sign = reflection_sign(name, (s & 1) ? -1.0 : 1.0, (s & 2) ? -1.0 : 1.0);
              const double partner = sign * double(full_field[full_index.at(ids[s])]);
              d.full_asymmetry = std::max(d.full_asymmetry, std::abs(partner - own) / scale);
            }
          }
          out.push_back(d);
        }
      });
    });
    return out;
  }

  // Largest displacement of a quarter particle from its initial position, m.
  [[nodiscard]] double largest_displacement() const {
    const Particles& q = quarter_.particles();
    double moved = 0.0;
    for (std::size_t i = 0; i < q.size(); ++i) {
      const auto& [x, y, z] = initial_.at(q.id[i]);
      moved = std::max(moved, std::hypot(q.x[i] - x, q.y[i] - y, q.z[i] - z));
    }
    return moved;
  }

 private:
  Simulation full_, quarter_;
  std::map<std::uint64_t, std::array<std::uint64_t, 4>> partners_;
  std::map<std::uint64_t, Position> initial_;
};

}  // namespace

// Why two tolerances. The pair sums run in a different order in the two runs, so they differ at round-off
// (1e-16 relative) from the first step. As long as nothing amplifies it they stay there: every field
// agrees to 1e-13 of its largest magnitude at every step until the first target particle starts to crush
// (step 6: it passes the elastic limit P_e of the P-alpha crush curve). From there on particles at P_e
// switch between crushing (distention rate ~-27 /s) and not from one step to the next, and whether a
// particle has crossed P_e in a given step is decided by round-off; the first decision that differs between
// the runs (step 12) leaves a difference of ~1e-12 and later ones ~1e-7 of the field's scale, which then
// persists (it does not grow: 1e-7 to 1e-6 from then to step 800). The full run is no more symmetric than
// that itself: its own mirror partners differ by as much. So the check after 0.02 s (724 steps: the
// contact, compaction and the late-stage switch at 0.01 s) is that every field of the quarter is within
// 1e-5 of its scale of the full run and no farther from it than the full run is from its own mirror image.
// How far that is, is itself round-off, so the comparison is made over all fields together: the largest
// difference of any field against the largest asymmetry of any field, and the geometric mean over the fields
// of each field's ratio, both at most 3. Measured (2026-12-06) over 32 realisations that differ only in
// round-off (the impact speed moved by 0-15 ulps, on the engine with std::cbrt in the h update and on one
// with a series for it): largest difference 2.6e-7 - 1.7e-6 of a field's scale, the ratio of the largest
// values 0.18-1.45, the geometric mean 0.47-1.70. A single field's ratio is not a yardstick: it ranged 0.9-11
// (a field whose own asymmetry came out small in that realisation), and the bound of 2 per field that this
// test first had failed in 11 of 16 of those realisations of the engine it was written for. A mirror error
// shows as a difference of the field's own size, far above 1e-5.
TEST(MirrorEngine, QuarterDomainEqualsTheFullDomainParticleByParticle) {
  FullAndQuarter runs;
  const double end_time = 0.02;
  // Step by step until a target particle of either run crushes: every field equal to 1e-13 before.
  const auto crushing = [&] {
    for (const Simulation* run : {&runs.full(), &runs.quarter()}) {
      const Particles& p = run->particles();
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (p.distention_rate[i] != 0.0) return true;
      }
    }
    return false;
  };
  double early = 0.0;
  std::uint64_t early_steps = 0;
  for (runs.step(end_time); !crushing(); runs.step(end_time)) {
    early_steps = runs.full().step_count();
    EXPECT_NEAR(runs.quarter().time(), runs.full().time(),
                1e-13 * runs.full().time());  // dt: min over particles
    for (const auto& d : runs.differences()) {
      EXPECT_LE(d.quarter_vs_full, 1e-13) << d.name << " after " << early_steps << " steps";
      early = std::max(early, d.quarter_vs_full);
    }
  }
  EXPECT_GE(early_steps, 4u);  // the shock needs that long to bring the first target particle to P_e

  while (runs.full().time() < end_time) runs.step(end_time);
  EXPECT_EQ(runs.quarter().time(), runs.full().time());
  EXPECT_EQ(runs.quarter().step_count(), runs.full().step_count());
  EXPECT_TRUE(runs.quarter().late_stage_active());
  const Box& box = runs.quarter().box();
  EXPECT_TRUE(box.mirror[0] && box.mirror[1] && !box.mirror[2]);
  double worst = 0.0, largest_asymmetry = 0.0, log_ratios = 0.0;
  int ratios = 0;
  std::string worst_field;
  for (const auto& d : runs.differences()) {
    EXPECT_LE(d.quarter_vs_full, 1e-5) << d.name;
    if (d.full_asymmetry == 0.0) {  // fields that never differ (mass, material, flags, ...)
      EXPECT_LE(d.quarter_vs_full, 1e-13) << d.name;
      continue;
    }
    if (d.quarter_vs_full > worst) worst = d.quarter_vs_full, worst_field = d.name;
    largest_asymmetry = std::max(largest_asymmetry, d.full_asymmetry);
    log_ratios += std::log(std::max(d.quarter_vs_full, 1e-300) / d.full_asymmetry);
    ++ratios;
  }
  ASSERT_GT(ratios, 20);
  const double typical_ratio = std::exp(log_ratios / ratios);
  EXPECT_LE(worst, 3.0 * largest_asymmetry) << worst_field;
  EXPECT_LE(typical_ratio, 3.0);
  const double moved = runs.largest_displacement();
  std::printf(
      "full vs quarter: to step %llu (before the first particle crushes) %.2e of the field's largest "
      "magnitude at most; after %llu steps to t = %.3g s %.2e (%s), %.2f x the full run's largest mirror "
      "asymmetry (%.2e), each field's ratio %.2f in the geometric mean; largest displacement %.3g m\n",
      static_cast<unsigned long long>(early_steps), early,
      static_cast<unsigned long long>(runs.quarter().step_count()), runs.quarter().time(), worst,
      worst_field.c_str(), worst / largest_asymmetry, largest_asymmetry, typical_ratio, moved);
  EXPECT_GT(moved, 0.02);  // the run did something: the projectile penetrated and was stopped

  // The conserved sums of the quarter are a quarter of the full domain's (mass, energy).
  const auto cq = runs.quarter().conserved(), cf = runs.full().conserved();
  EXPECT_NEAR(4.0 * cq.mass, cf.mass, 1e-12 * cf.mass);
  EXPECT_NEAR(4.0 * cq.total_energy, cf.total_energy, 1e-8 * std::abs(cf.total_energy));
  EXPECT_NEAR(4.0 * cq.kinetic_energy, cf.kinetic_energy, 1e-6 * cf.kinetic_energy);
}

TEST(MirrorEngine, ResumedQuarterRunEqualsUninterruptedRunBitwise) {
  auto config = [](std::uint64_t max_steps) {
    ImpactConfig c = small_impact(DomainSymmetry::quarter);
    c.simulation.run.max_steps = max_steps;
    c.simulation.output.checkpoint_interval_steps = 10;
    return c;
  };
  RunOptions options;
  options.progress = false;
  options.log = false;
  const auto straight = scratch("straight");
  options.output_directory = straight;
  run_impact(config(45), options);
  // A run stopped after 23 steps whose last checkpoint is from step 20 (as in test_engine_restart.cpp).
  const auto resumed = scratch("resumed");
  options.output_directory = resumed;
  run_impact(config(23), options);
  const auto partial = scratch("partial");
  options.output_directory = partial;
  run_impact(config(20), options);
  fs::copy_file(partial / "checkpoint.h5", resumed / "checkpoint.h5", fs::copy_options::overwrite_existing);
  options.output_directory = resumed;
  options.resume = true;
  const auto summary = run_impact(config(45), options);
  EXPECT_TRUE(summary.run.resumed);
  EXPECT_EQ(summary.run.steps, 45u);

  RunAttributes a, b;
  const Particles one = read_checkpoint(straight / "checkpoint.h5", &a);
  const Particles two = read_checkpoint(resumed / "checkpoint.h5", &b);
  EXPECT_EQ(a.time, b.time);
  EXPECT_EQ(a.texts.at("symmetry"), "quarter");
  EXPECT_EQ(a.numbers.at("next_time_step"), b.numbers.at("next_time_step"));
  engine_test::expect_identical_particles(one, two);
  EXPECT_EQ(read_text(straight / "conservation.csv"), read_text(resumed / "conservation.csv"));
  for (const auto& dir : {straight, resumed, partial}) fs::remove_all(dir);
}

TEST(MirrorEngine, QuarterRunIndependentOfThreadCount) {
  ImpactConfig config = small_impact(DomainSymmetry::quarter);
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  auto one = impact_test::run_to(config, 0.02);
  omp_set_num_threads(2);
  auto two = impact_test::run_to(config, 0.02);
  omp_set_num_threads(threads);
  EXPECT_EQ(one.step_count(), two.step_count());
  engine_test::expect_identical_particles(one.particles(), two.particles());
}
