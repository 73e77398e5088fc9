#include "craterkit/dem/granular_bed.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <map>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include "craterkit/common/atomic_file.hpp"
#include "craterkit/common/checks.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/dem/lammps_process.hpp"
#include "granular_script.hpp"

namespace craterkit::dem {

namespace {

// Volume of a sphere (centre height z, radius r) below the plane at height h.
double volume_below(double z, double r, double h) {
  if (h >= z + r) return 4.0 / 3.0 * std::numbers::pi * r * r * r;
  if (h <= z - r) return 0.0;
  const double cap = h - (z - r);
  return std::numbers::pi * cap * cap * (3.0 * r - cap) / 3.0;
}

// The grains before settling: a loose simple-cubic lattice (spacing >= 1.05 d_max, fitting the periodic box
// exactly) filled layer by layer from the floor up with enough grains for 1.2 times the depth at a packing
// fraction of 0.64, each displaced sideways by up to 5 % of the spacing so that the lattice does not stack.
Grains loose_lattice(const BedSpec& spec, std::mt19937_64& random) {
  const double min_spacing = 1.05 * spec.grain_sizes.max_diameter;
  const auto nx = static_cast<long>(std::floor(spec.length_x / min_spacing));
  const auto ny = static_cast<long>(std::floor(spec.length_y / min_spacing));
  const double sx = spec.length_x / static_cast<double>(nx);
  const double sy = spec.length_y / static_cast<double>(ny);
  const double sz = min_spacing;
  const double grain_volume = std::numbers::pi / 6.0 * spec.grain_sizes.mean_cubed_diameter();
  const auto wanted =
      static_cast<long>(std::ceil(0.64 * spec.length_x * spec.length_y * 1.2 * spec.depth / grain_volume));
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  Grains grains;
  for (long n = 0; n < wanted; ++n) {
    const long layer = n / (nx * ny);
    const long in_layer = n % (nx * ny);
    double x = (static_cast<double>(in_layer % nx) + 0.5 + jitter(random)) * sx;
    double y = (static_cast<double>(in_layer / nx) + 0.5 + jitter(random)) * sy;
    const double z = (static_cast<double>(layer) + 0.5) * sz;
    const double d = spec.grain_sizes.draw(random);
    if (spec.side_walls) {  // no grain may start through a wall
      x = std::clamp(x, 0.5 * d, spec.length_x - 0.5 * d);
      y = std::clamp(y, 0.5 * d, spec.length_y - 0.5 * d);
    }
    grains.add(x, y, z, d, spec.grain_density);
  }
  return grains;
}

double top_of(const Grains& grains) {
  double top = 0;
  for (std::size_t i = 0; i < grains.size(); ++i) top = std::max(top, grains.z[i] + 0.5 * grains.diameter[i]);
  return top;
}

// The settling script: settle, remove every grain whose centre lies above the depth, settle again, dump.
std::string settle_script(const BedSpec& spec, double time_step, long max_steps) {
  GranularScript script;
  script.title = "craterkit: a granular bed settled under gravity (docs/dem.md, \"Settled bed\")";
  script.boundary = spec.side_walls ? "f f fm" : "p p fm";
  script.data_file = "grains.data";
  script.contact_model =
      lammps_contact_model(spec.contact, spec.grain_sizes.mean_diameter(), spec.grain_density);
  if (spec.side_walls) {
    const std::string frictionless = lammps_contact_model(
        frictionless_wall(spec.contact), spec.grain_sizes.mean_diameter(), spec.grain_density);
    script.extra_fixes = fmt::format(
        "fix side_x all wall/gran granular {model} xplane 0.0 {x:.17g}\n"
        "fix side_y all wall/gran granular {model} yplane 0.0 {y:.17g}\n",
        fmt::arg("model", frictionless), fmt::arg("x", spec.length_x), fmt::arg("y", spec.length_y));
  }
  script.gravity = spec.gravity;
  script.skin = 0.25 * spec.grain_sizes.max_diameter;
  script.time_step = time_step;
  script.check_every = rest_check_interval(max_steps);
  const double rest = rest_speed(spec.rest_speed_fraction, spec.gravity, spec.grain_sizes.mean_diameter());
  return granular_script_start(script) +
         fmt::format(R"(fix rest all halt {check} v_mean_speed < {rest:.17g} error continue
run {steps}
print "first_settle ${{mean_speed}}" file settle_status.txt
region above block INF INF INF INF {depth:.17g} INF units box
delete_atoms region above
velocity all set 0 0 0
unfix rest
fix rest all halt {check} v_mean_speed < {rest:.17g} error continue
run {steps}
print "second_settle ${{mean_speed}}" append settle_status.txt
write_dump all custom bed.dump {columns} modify sort id format float %.17g
)",
                     fmt::arg("check", script.check_every), fmt::arg("rest", rest),
                     fmt::arg("steps", max_steps), fmt::arg("depth", spec.depth),
                     fmt::arg("columns", dump_columns));
}

std::map<std::string, double> read_status(const std::filesystem::path& path) {
  std::map<std::string, double> values;
  std::ifstream in(path);
  std::string name;
  double value = 0;
  while (in >> name >> value) values[name] = value;
  return values;
}

SettledBed describe(const BedSpec& spec, Grains grains) {
  // LAMMPS maps a grain that crossed a periodic side back into the box only when it rebuilds its lists.
  for (std::size_t i = 0; i < grains.size() && !spec.side_walls; ++i) {
    grains.x[i] -= spec.length_x * std::floor(grains.x[i] / spec.length_x);
    grains.y[i] -= spec.length_y * std::floor(grains.y[i] / spec.length_y);
  }
  SettledBed bed;
  bed.box = Box{0, spec.length_x, 0, spec.length_y, 0, top_of(grains)};
  bed.surface_height = mean_surface_height(grains, bed.box, spec.grain_sizes.max_diameter);
  const double margin = 2.0 * spec.grain_sizes.max_diameter;
  bed.packing_fraction = packing_fraction_between(grains, bed.box, margin, bed.surface_height - margin);
  bed.bulk_density = bed.packing_fraction * spec.grain_density;
  bed.grains = std::move(grains);
  return bed;
}

}  // namespace

void check_bed_spec(const BedSpec& spec) {
  require_positive(spec.length_x, "bed.length_x");
  require_positive(spec.length_y, "bed.length_y");
  require_positive(spec.depth, "bed.depth");
  check_grain_sizes(spec.grain_sizes, "bed.grain_sizes");
  require_positive(spec.grain_density, "bed.grain_density");
  check_grain_contact(spec.contact, "bed.contact");
  require_positive(spec.gravity, "bed.gravity");
  require_in_range(spec.rest_speed_fraction, "bed.rest_speed_fraction", 0.0, 1.0, true, false);
  require_in_range(spec.processes, "bed.processes", 1, 4096);
  const double d = spec.grain_sizes.max_diameter;
  for (const auto& [name, length] :
       {std::pair{"bed.length_x", spec.length_x}, std::pair{"bed.length_y", spec.length_y},
        std::pair{"bed.depth", spec.depth}}) {
    if (length < 4.0 * 1.05 * d)
      throw InputError(fmt::format("{}: value {:g} m is under 4.2 largest grains ({:g} m): allowed >= {:g} m",
                                   name, length, d, 4.2 * d));
  }
}

std::string bed_key(const BedSpec& spec) {
  const auto& c = spec.contact;
  return fmt::format(
      "craterkit settled bed v1: length_x {:.17g} length_y {:.17g} depth {:.17g} min_diameter {:.17g} "
      "max_diameter {:.17g} grain_density {:.17g} youngs_modulus {:.17g} poisson_ratio {:.17g} restitution "
      "{:.17g} sliding_friction {:.17g} rolling_friction {:.17g} gravity {:.17g} seed {} rest_speed_fraction "
      "{:.17g}{}",
      spec.length_x, spec.length_y, spec.depth, spec.grain_sizes.min_diameter, spec.grain_sizes.max_diameter,
      spec.grain_density, c.youngs_modulus, c.poisson_ratio, c.restitution, c.sliding_friction,
      c.rolling_friction, spec.gravity, spec.seed, spec.rest_speed_fraction,
      spec.side_walls ? " side_walls" : "");
}

std::string bed_hash(const BedSpec& spec) {
  // FNV-1a, 64 bits.
  std::uint64_t hash = 14695981039346656037ULL;
  for (const unsigned char c : bed_key(spec)) {
    hash ^= c;
    hash *= 1099511628211ULL;
  }
  return fmt::format("{:016x}", hash);
}

SettledBed settle_bed(const BedSpec& spec, const std::filesystem::path& folder,
                      const ProgressLine& progress) {
  check_bed_spec(spec);
  std::filesystem::create_directories(folder);
  std::mt19937_64 random(spec.seed);
  const Grains loose = loose_lattice(spec, random);
  // Time step: a fiftieth of the Hertz contact time of the smallest grains at the speed of a fall from the
  // top of the loose lattice (Johnson 1985, sec. 11.4); grains settle within 50 free-fall times of that
  // height.
  const double drop_height = top_of(loose);
  const double impact_speed = std::sqrt(2.0 * spec.gravity * drop_height);
  const double time_step =
      hertz_contact_time(spec.contact, spec.grain_sizes.min_diameter, spec.grain_density, impact_speed) /
      50.0;
  const auto max_steps =
      static_cast<long>(std::ceil(50.0 * std::sqrt(drop_height / spec.gravity) / time_step));
  write_lammps_data(folder / "grains.data", loose,
                    Box{0, spec.length_x, 0, spec.length_y, 0, 1.1 * drop_height});
  write_atomically(folder / "settle.in", [&](const std::filesystem::path& tmp) {
    std::ofstream(tmp) << settle_script(spec, time_step, max_steps);
  });
  std::filesystem::remove(folder / "settle_status.txt");
  const double rest = rest_speed(spec.rest_speed_fraction, spec.gravity, spec.grain_sizes.mean_diameter());
  LammpsPoll poll;
  if (progress) {
    const auto start = std::chrono::steady_clock::now();
    poll.call = [&] {
      // thermo_style custom step atoms ke v_mean_speed
      const auto last = last_thermo_values(folder / "settle.log", 4);
      const long step = last.empty() ? 0 : std::lround(last[0]);
      const double mean_speed = last.empty() ? 0.0 : last[3];
      progress(fmt::format(
          "dem: settling: step {} (at most {} in each of 2 settlings), mean grain speed {:.3g} m/s (at rest "
          "below {:.3g}), {:.0f} s elapsed",
          step, max_steps, mean_speed, rest,
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()));
    };
  }
  run_lammps({folder, "settle.in", spec.processes}, poll);
  const auto status = read_status(folder / "settle_status.txt");
  for (const char* stage : {"first_settle", "second_settle"}) {
    const auto found = status.find(stage);
    if (found == status.end())
      throw std::runtime_error(
          fmt::format("{}: LAMMPS did not report {}", (folder / "settle_status.txt").string(), stage));
    if (!(found->second < rest))
      throw std::runtime_error(
          fmt::format("the bed did not come to rest within {} steps ({}: mean grain speed {:g} m/s, at rest "
                      "below {:g} m/s); "
                      "see {}",
                      max_steps, stage, found->second, rest, (folder / "settle.log").string()));
  }
  SettledBed bed = describe(spec, read_lammps_dump(folder / "bed.dump"));
  if (bed.surface_height < spec.depth - spec.grain_sizes.max_diameter)
    throw std::runtime_error(
        fmt::format("the settled bed's surface lies at {:g} m, more than a grain below the depth "
                    "{:g} m: too few grains were dropped (see {})",
                    bed.surface_height, spec.depth, (folder / "settle.log").string()));
  return bed;
}

SettledBed settled_bed_cached(const BedSpec& spec, const std::filesystem::path& cache,
                              const ProgressLine& progress) {
  check_bed_spec(spec);
  const std::string hash = bed_hash(spec);
  const auto dump = cache / ("bed-" + hash + ".dump");
  const auto key_file = cache / ("bed-" + hash + ".key");
  const std::string key = bed_key(spec);
  if (std::filesystem::exists(dump) && std::filesystem::exists(key_file)) {
    std::ifstream in(key_file);
    std::string stored;
    std::getline(in, stored);
    if (stored == key) return describe(spec, read_lammps_dump(dump));
  }
  SettledBed bed = settle_bed(spec, cache / ("bed-" + hash), progress);
  // The dump first, the key last: a key is only ever beside a complete dump.
  std::filesystem::copy_file(cache / ("bed-" + hash) / "bed.dump", temporary_sibling(dump),
                             std::filesystem::copy_options::overwrite_existing);
  std::filesystem::rename(temporary_sibling(dump), dump);
  write_atomically(key_file, [&](const std::filesystem::path& tmp) { std::ofstream(tmp) << key << '\n'; });
  return bed;
}

double packing_fraction_between(const Grains& grains, const Box& box, double low, double high) {
  if (!(high > low))
    throw std::invalid_argument(fmt::format("packing_fraction_between: high {:g} <= low {:g}", high, low));
  double volume = 0;
  for (std::size_t i = 0; i < grains.size(); ++i) {
    const double r = 0.5 * grains.diameter[i];
    volume += volume_below(grains.z[i], r, high) - volume_below(grains.z[i], r, low);
  }
  return volume / ((box.x_high - box.x_low) * (box.y_high - box.y_low) * (high - low));
}

double contact_elastic_energy(const Grains& grains, const GrainContact& contact) {
  double cell = 0;
  for (std::size_t i = 0; i < grains.size(); ++i) cell = std::max(cell, grains.diameter[i]);
  if (grains.size() < 2) return 0.0;
  auto index = [&](double c) { return static_cast<long>(std::floor(c / cell)); };
  auto key = [](long a, long b, long c) {
    constexpr long offset = 1L << 20;
    return (static_cast<std::uint64_t>(a + offset) << 42) | (static_cast<std::uint64_t>(b + offset) << 21) |
           static_cast<std::uint64_t>(c + offset);
  };
  std::map<std::uint64_t, std::vector<std::size_t>> cells;
  for (std::size_t i = 0; i < grains.size(); ++i)
    cells[key(index(grains.x[i]), index(grains.y[i]), index(grains.z[i]))].push_back(i);
  double energy = 0;
  for (std::size_t i = 0; i < grains.size(); ++i) {
    const long cx = index(grains.x[i]), cy = index(grains.y[i]), cz = index(grains.z[i]);
    for (long a = cx - 1; a <= cx + 1; ++a)
      for (long b = cy - 1; b <= cy + 1; ++b)
        for (long c = cz - 1; c <= cz + 1; ++c) {
          const auto found = cells.find(key(a, b, c));
          if (found == cells.end()) continue;
          for (const std::size_t j : found->second) {
            if (j <= i) continue;
            const double dx = grains.x[j] - grains.x[i], dy = grains.y[j] - grains.y[i],
                         dz = grains.z[j] - grains.z[i];
            const double ri = 0.5 * grains.diameter[i], rj = 0.5 * grains.diameter[j];
            const double overlap = ri + rj - std::sqrt(dx * dx + dy * dy + dz * dz);
            if (overlap > 0) energy += hertz_elastic_energy(contact, ri * rj / (ri + rj), overlap);
          }
        }
  }
  return energy;
}

double mean_surface_height(const Grains& grains, const Box& box, double cell) {
  const auto nx = std::max(1L, static_cast<long>(std::floor((box.x_high - box.x_low) / cell)));
  const auto ny = std::max(1L, static_cast<long>(std::floor((box.y_high - box.y_low) / cell)));
  std::vector<double> top(static_cast<std::size_t>(nx * ny), -1.0);
  for (std::size_t i = 0; i < grains.size(); ++i) {
    const auto cx =
        std::clamp(static_cast<long>((grains.x[i] - box.x_low) / (box.x_high - box.x_low) * nx), 0L, nx - 1);
    const auto cy =
        std::clamp(static_cast<long>((grains.y[i] - box.y_low) / (box.y_high - box.y_low) * ny), 0L, ny - 1);
    auto& t = top[static_cast<std::size_t>(cy * nx + cx)];
    t = std::max(t, grains.z[i] + 0.5 * grains.diameter[i]);
  }
  double sum = 0;
  long filled = 0;
  for (const double t : top) {
    if (t >= 0) {
      sum += t;
      ++filled;
    }
  }
  return filled > 0 ? sum / static_cast<double>(filled) : 0.0;
}

}  // namespace craterkit::dem
