#include "craterkit/dem/column_collapse.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <numbers>
#include <stdexcept>

#include "craterkit/common/atomic_file.hpp"
#include "craterkit/common/checks.hpp"
#include "craterkit/dem/granular_bed.hpp"
#include "craterkit/dem/lammps_files.hpp"
#include "craterkit/dem/lammps_process.hpp"
#include "granular_script.hpp"

namespace craterkit::dem {

namespace {

std::string collapse_script(const ColumnSpec& spec, double wall_x, double time_step, long max_steps) {
  GranularScript script;
  script.title =
      "craterkit: a granular column collapses against its back wall (docs/dem.md, \"Angle of repose\")";
  script.boundary = "f p fm";
  script.data_file = "column.data";
  script.contact_model =
      lammps_contact_model(spec.contact, spec.grain_sizes.mean_diameter(), spec.grain_density);
  script.extra_fixes = fmt::format("fix walls all wall/gran granular {} xplane {:.17g} {:.17g}\n",
                                   script.contact_model, wall_x, spec.floor_length);
  script.gravity = spec.gravity;
  script.skin = 0.25 * spec.grain_sizes.max_diameter;
  script.time_step = time_step;
  script.check_every = rest_check_interval(max_steps);
  const double rest = rest_speed(spec.rest_speed_fraction, spec.gravity, spec.grain_sizes.mean_diameter());
  // The drag is defined after the integrator, as in the runs of data/dem/repose_calibration.csv (LAMMPS adds
  // the fixes' forces in the order they were defined). The first `check` steps start the collapse before the
  // rest check is armed (the settled column is at rest).
  const std::string drag =
      spec.drag_time > 0
          ? fmt::format("fix drag all langevin 0 0 {:.17g} {} omega yes\n", spec.drag_time, spec.seed)
          : std::string("# no drag: a free collapse\n");
  return granular_script_start(script) + drag +
         fmt::format(R"(variable collapse_time equal time
run {check}
fix rest all halt {check} v_mean_speed < {rest:.17g} error continue
run {steps}
print "collapse ${{mean_speed}} ${{collapse_time}}" file collapse_status.txt
write_dump all custom deposit.dump {columns} modify sort id format float %.17g
)",
                     fmt::arg("check", script.check_every), fmt::arg("rest", rest),
                     fmt::arg("steps", max_steps), fmt::arg("columns", dump_columns));
}

}  // namespace

Deposit collapse_column(const ColumnSpec& spec, const std::filesystem::path& folder) {
  require_positive(spec.floor_length - spec.width, "column.floor_length - column.width");
  require_non_negative(spec.drag_time, "column.drag_time");
  BedSpec bed_spec;
  bed_spec.length_x = spec.width;
  bed_spec.length_y = spec.thickness;
  bed_spec.depth = spec.height;
  bed_spec.grain_sizes = spec.grain_sizes;
  bed_spec.grain_density = spec.grain_density;
  bed_spec.contact = spec.contact;
  bed_spec.gravity = spec.gravity;
  bed_spec.seed = spec.seed;
  bed_spec.rest_speed_fraction = spec.rest_speed_fraction;
  bed_spec.processes = spec.processes;
  std::filesystem::create_directories(folder);
  SettledBed column = settle_bed(bed_spec, folder / "column");

  // The periodic seam becomes the back wall and the gate: the wall stands at the edge of the grain reaching
  // furthest back, so that no grain starts inside it.
  double wall_x = 0;
  for (std::size_t i = 0; i < column.grains.size(); ++i)
    wall_x = std::min(wall_x, column.grains.x[i] - 0.5 * column.grains.diameter[i]);
  const double time_step = hertz_contact_time(spec.contact, spec.grain_sizes.min_diameter, spec.grain_density,
                                              std::sqrt(2.0 * spec.gravity * spec.height)) /
                           50.0;
  // A free collapse rests within about 10 sqrt(H/g); a dragged one creeps for longer.
  const double longest = (spec.drag_time > 0 ? 200.0 : 60.0) * std::sqrt(spec.height / spec.gravity);
  const auto max_steps = static_cast<long>(std::ceil(longest / time_step));
  write_lammps_data(folder / "column.data", column.grains,
                    Box{wall_x, spec.floor_length, 0, spec.thickness, 0, 2.0 * spec.height});
  write_atomically(folder / "collapse.in", [&](const std::filesystem::path& tmp) {
    std::ofstream(tmp) << collapse_script(spec, wall_x, time_step, max_steps);
  });
  std::filesystem::remove(folder / "collapse_status.txt");
  run_lammps({folder, "collapse.in", spec.processes});
  std::ifstream status(folder / "collapse_status.txt");
  std::string word;
  double mean_speed = 0;
  Deposit deposit;
  if (!(status >> word >> mean_speed >> deposit.collapse_time) || word != "collapse")
    throw std::runtime_error(
        fmt::format("{}: LAMMPS did not report the collapse", (folder / "collapse_status.txt").string()));
  const double rest = rest_speed(spec.rest_speed_fraction, spec.gravity, spec.grain_sizes.mean_diameter());
  if (!(mean_speed < rest))
    throw std::runtime_error(
        fmt::format("the column did not come to rest within {} steps (mean grain speed {:g} m/s, "
                    "at rest below {:g} m/s); see {}",
                    max_steps, mean_speed, rest, (folder / "collapse.log").string()));
  deposit.grains = read_lammps_dump(folder / "deposit.dump");
  deposit.profile = surface_profile(deposit.grains, spec.floor_length, spec.grain_sizes.max_diameter);
  deposit.flank = flank_slope(deposit.profile, 0.2, 0.8);
  return deposit;
}

SurfaceProfile surface_profile(const Grains& grains, double length, double cell) {
  const auto columns = static_cast<std::size_t>(std::ceil(length / cell));
  SurfaceProfile profile;
  profile.height.assign(columns, 0.0);
  for (std::size_t c = 0; c < columns; ++c) profile.x.push_back((static_cast<double>(c) + 0.5) * cell);
  for (std::size_t i = 0; i < grains.size(); ++i) {
    if (grains.x[i] < 0) continue;
    const auto c = static_cast<std::size_t>(grains.x[i] / cell);
    if (c >= columns) continue;
    profile.height[c] = std::max(profile.height[c], grains.z[i] + 0.5 * grains.diameter[i]);
  }
  return profile;
}

}  // namespace craterkit::dem
