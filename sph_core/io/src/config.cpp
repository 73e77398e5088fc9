#include "craterkit/sph/io/config.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"

namespace craterkit::sph {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr std::int64_t int_max = std::numeric_limits<std::int64_t>::max();

void read_run(TomlTable s, SimulationConfig& c) {
  if (!s.contains("end_time")) s.fail("end_time", "missing: the simulated end time in s (> 0)");
  c.run.end_time = s.number("end_time", 0.0, 0.0, inf, true);
  c.run.max_steps = static_cast<std::uint64_t>(s.integer("max_steps", c.run.max_steps, 0, int_max));
  const auto& g0 = c.solver.gravity;
  const auto g = s.numbers("gravity").value_or(std::vector<double>{g0[0], g0[1], g0[2]});
  if (g.size() != 3) s.fail("gravity", "expected 3 components [gx, gy, gz], got " + std::to_string(g.size()));
  c.solver.gravity = {g[0], g[1], g[2]};
  s.finish();
}

void read_kernel(TomlTable s, SolverParameters& c) {
  const std::string type =
      s.text("type", std::string(kernel_name(c.kernel)), {"cubic_spline", "wendland_c2"});
  c.kernel = type == "wendland_c2" ? KernelType::wendland_c2 : KernelType::cubic_spline;
  auto& h = c.smoothing;
  h.eta = s.number("eta", h.eta, 0.8, 3.0);
  h.min_smoothing_length = s.number("min_smoothing_length", h.min_smoothing_length, 0.0, inf);
  h.max_smoothing_length = s.number("max_smoothing_length", h.max_smoothing_length, 0.0, inf, true);
  h.max_smoothing_ratio = s.number("max_smoothing_ratio", h.max_smoothing_ratio, 1.0, inf);
  h.neighbour_band = s.number("neighbour_band", h.neighbour_band, 0.0, 1.0, true);
  const std::string density =
      s.text("density", std::string(density_method_name(c.density)), {"continuity", "summation"});
  c.density = density == "summation" ? DensityMethod::summation : DensityMethod::continuity;
  if (h.max_smoothing_length < h.min_smoothing_length) {
    s.fail("max_smoothing_length", "must not be below kernel.min_smoothing_length");
  }
  s.finish();
}

void read_viscosity(TomlTable s, ArtificialViscosity& v) {
  v.alpha = s.number("alpha", v.alpha, 0.0, 10.0);
  v.beta = s.number("beta", v.beta, 0.0, 20.0);
  const std::string sw =
      s.text("switch", std::string(viscosity_switch_name(v.viscosity_switch)), {"none", "morris_monaghan"});
  v.viscosity_switch = sw == "morris_monaghan" ? ViscositySwitch::morris_monaghan : ViscositySwitch::none;
  v.alpha_min = s.number("alpha_min", v.alpha_min, 0.0, 10.0);
  if (v.alpha_min > v.alpha)
    s.fail("alpha_min", "value " + format_number(v.alpha_min) + " exceeds viscosity.alpha");
  v.decay_factor = s.number("decay_factor", v.decay_factor, 0.0, 10.0, true);
  v.epsilon = s.number("epsilon", v.epsilon, 0.0, 1.0, true);
  v.balsara = s.boolean("balsara", v.balsara);
  s.finish();
}

void read_time_step(TomlTable s, SolverParameters& c) {
  auto& t = c.time_step;
  t.courant = s.number("courant", t.courant, 0.0, 1.0, true);
  t.acceleration_factor = s.number("acceleration_factor", t.acceleration_factor, 0.0, 1.0, true);
  t.density_change = s.number("density_change", t.density_change, 0.0, 1.0, true);
  t.energy_change = s.number("energy_change", t.energy_change, 0.0, 1.0);
  t.energy_floor = s.number("energy_floor", t.energy_floor, 0.0, inf);
  t.max_step = s.number("max_step", t.max_step, 0.0, inf, true);
  t.velocity_change = s.number("velocity_change", t.velocity_change, 0.0, 1.0);
  // Block steps need the integrated (continuity) density: a summed density would need every neighbour's
  // density at every substep.
  const int block_default = c.density == DensityMethod::continuity ? t.block_levels : 0;
  t.block_levels = static_cast<int>(s.integer("block_levels", block_default, 0, 30));
  if (t.block_levels > 0 && c.density == DensityMethod::summation) {
    s.fail("block_levels",
           "block time steps need kernel.density = \"continuity\" (a summed density would "
           "need every neighbour's density at every substep)");
  }
  s.finish();
}

void read_neighbours(TomlTable s, SolverParameters& c) {
  auto& n = c.neighbours;
  n.search.skin = s.number("skin", n.search.skin, 0.0, 1.0);
  n.sort_interval = static_cast<std::uint64_t>(s.integer("sort_interval", n.sort_interval, 0, int_max));
  n.halo_skin = s.number("halo_skin", n.halo_skin, 0.0, 2.0);
  s.finish();
}

void read_output(TomlTable s, OutputParameters& o) {
  o.snapshot_times = s.numbers("snapshot_times").value_or(o.snapshot_times);
  for (std::size_t i = 0; i < o.snapshot_times.size(); ++i) {
    if (o.snapshot_times[i] < 0.0 || (i > 0 && o.snapshot_times[i] <= o.snapshot_times[i - 1])) {
      s.fail("snapshot_times", "element " + std::to_string(i) + " (" + format_number(o.snapshot_times[i]) +
                                   "): times must be >= 0 and strictly ascending");
    }
  }
  o.checkpoint_interval_steps = static_cast<std::uint64_t>(
      s.integer("checkpoint_interval_steps", o.checkpoint_interval_steps, 0, int_max));
  o.checkpoint_interval_seconds =
      s.number("checkpoint_interval_seconds", o.checkpoint_interval_seconds, 0.0, inf);
  o.conservation_log = s.boolean("conservation_log", o.conservation_log);
  o.compression = static_cast<int>(s.integer("compression", o.compression, 0, 9));
  s.finish();
}

}  // namespace

std::string read_problem_setup(TomlTable& root, const std::vector<std::string>& setups) {
  TomlTable problem = root.table("problem");
  std::string list;
  for (const auto& s : setups) list += (list.empty() ? "\"" : ", \"") + s + "\"";
  const std::string setup = problem.text("setup", "", setups);
  if (setup.empty()) problem.fail("setup", "missing: one of " + list);
  for (const auto& other : setups) {
    if (other != setup && root.contains(other)) {
      throw InputError(root.source() + ": table [" + other + "] given but problem.setup = \"" + setup + "\"");
    }
  }
  return setup;
}

SimulationConfig parse_simulation_config(TomlTable& root, const SimulationConfig& defaults) {
  SimulationConfig c = defaults;
  {
    TomlTable problem = root.table("problem");
    problem.accept("setup");  // the scenario's (read_problem_setup)
    c.name = problem.text("name", c.name);
    problem.finish();
  }
  read_run(root.table("run"), c);
  read_kernel(root.table("kernel"), c.solver);
  read_viscosity(root.table("viscosity"), c.solver.viscosity);
  {
    TomlTable s = root.table("artificial_stress");
    c.solver.artificial_stress = s.number("epsilon", c.solver.artificial_stress, 0.0, 1.0);
    s.finish();
  }
  read_time_step(root.table("time_step"), c.solver);
  read_neighbours(root.table("neighbours"), c.solver);
  read_output(root.table("output"), c.output);
  check_checkpoint_timing(c, root.source() + ": ");
  return c;
}

void check_checkpoint_timing(const SimulationConfig& config, const std::string& where) {
  if (config.output.checkpoint_interval_seconds > 0 && config.solver.neighbours.sort_interval == 0) {
    throw InputError(
        where +
        "output.checkpoint_interval_seconds = " + format_number(config.output.checkpoint_interval_seconds) +
        " with neighbours.sort_interval = 0 is not allowed: without curve sorts every checkpoint has to "
        "rebuild "
        "the neighbour lists, so checkpoints at wall-clock moments would make the result depend on the "
        "machine's load. Set neighbours.sort_interval > 0 (default 20), or "
        "output.checkpoint_interval_seconds = "
        "0 (with checkpoint_interval_steps = N for checkpoints by step count)");
  }
}

}  // namespace craterkit::sph
