#include "craterkit/sph/io/config.hpp"

#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include "craterkit/common/input_error.hpp"
#include "craterkit/impact/impact_config.hpp"
#include "toml_keys.hpp"

namespace craterkit::sph {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();
constexpr std::int64_t int_max = std::numeric_limits<std::int64_t>::max();

}  // namespace

std::string setup_name(const SetupParameters& setup) {
  switch (setup.index()) {
    case 0:
      return "sedov";
    case 1:
      return "sod";
    case 2:
      return "plates";
    default:
      return "impact";
  }
}

SimulationConfig parse_simulation_config(const std::string& toml_text, const std::string& source) {
  toml::table root;
  try {
    root = toml::parse(toml_text, source);
  } catch (const toml::parse_error& e) {
    std::ostringstream s;
    s << source << ":" << e.source().begin.line << ":" << e.source().begin.column
      << ": TOML syntax error: " << e.description();
    throw InputError(s.str());
  }

  const std::vector<std::string> tables = {
      "problem",   "sedov",     "sod",        "plates", "impact",     "run",    "kernel",
      "viscosity", "time_step", "neighbours", "output", "late_stage", "crater", "artificial_stress"};
  for (const auto& [k, node] : root) {
    const std::string name(k.str());
    bool known = false;
    for (const auto& t : tables) known = known || t == name;
    if (!known) {
      throw InputError(
          source + ": unknown table or key " + name +
          " (allowed: problem, sedov, sod, plates, impact, run, kernel, viscosity, time_step, neighbours, "
          "output, late_stage, crater, artificial_stress)");
    }
    if (!node.is_table()) throw InputError(source + ": " + name + " must be a table ([" + name + "])");
  }
  auto section = [&](const std::string& name) { return TomlKeys(root[name].as_table(), name, source); };

  SimulationConfig c;
  {
    TomlKeys s = section("problem");
    c.name = s.text("name", "simulation");
    const std::string setup = s.text("setup", "", {"sedov", "sod", "plates", "impact"});
    if (setup.empty()) s.fail("setup", "missing: one of \"sedov\", \"sod\", \"plates\", \"impact\"");
    s.finish();
    for (const char* other : {"sedov", "sod", "plates", "impact"}) {
      if (other != setup && root.contains(other)) {
        throw InputError(source + ": table [" + std::string(other) + "] given but problem.setup = \"" +
                         setup + "\"");
      }
    }
    if (setup == "sedov") {
      TomlKeys t = section("sedov");
      SedovSetup p;
      p.material = t.text("material", p.material);
      p.particles_per_side = static_cast<int>(t.integer("particles_per_side", p.particles_per_side, 4, 400));
      p.box_size = t.number("box_size", p.box_size, 0.0, inf, true);
      p.density = t.number("density", p.density, 0.0, inf, true);
      p.blast_energy = t.number("blast_energy", p.blast_energy, 0.0, inf, true);
      p.background_energy = t.number("background_energy", p.background_energy, 0.0, inf);
      p.blast_radius = t.number("blast_radius", p.blast_radius, 0.0, 0.25 * p.box_size);
      t.finish();
      c.setup = p;
    } else if (setup == "sod") {
      TomlKeys t = section("sod");
      SodSetup p;
      p.material = t.text("material", p.material);
      p.left_particles_per_length =
          static_cast<int>(t.integer("left_particles_per_length", p.left_particles_per_length, 4, 100000));
      p.cross_section = t.number("cross_section", p.cross_section, 0.0, 1.0, true);
      p.left_density = t.number("left_density", p.left_density, 0.0, inf, true);
      p.left_pressure = t.number("left_pressure", p.left_pressure, 0.0, inf, true);
      p.right_density = t.number("right_density", p.right_density, 0.0, inf, true);
      p.right_pressure = t.number("right_pressure", p.right_pressure, 0.0, inf, true);
      t.finish();
      c.setup = p;
    } else if (setup == "impact") {
      const toml::table* impact = root["impact"].as_table();
      c.setup = parse_impact_setup(impact != nullptr ? *impact : toml::table{}, source);
    } else {
      TomlKeys t = section("plates");
      PlateImpactSetup p;
      p.projectile_material = t.text("projectile_material", p.projectile_material);
      p.target_material = t.text("target_material", p.target_material);
      p.impact_velocity = t.number("impact_velocity", p.impact_velocity, 0.0, inf, true);
      p.projectile_thickness = t.number("projectile_thickness", p.projectile_thickness, 0.0, inf, true);
      p.target_thickness = t.number("target_thickness", p.target_thickness, 0.0, inf, true);
      p.particle_spacing = t.number("particle_spacing", p.particle_spacing, 0.0, inf, true);
      p.cross_section_particles =
          static_cast<int>(t.integer("cross_section_particles", p.cross_section_particles, 4, 1000));
      if (p.particle_spacing > 0.5 * std::min(p.projectile_thickness, p.target_thickness)) {
        t.fail("particle_spacing",
               "value " + format_number(p.particle_spacing) + " too large: at most half the thinner plate");
      }
      t.finish();
      c.setup = p;
    }
  }
  // Impacts change some defaults below (docs/simulate.md, "Defaults for impacts").
  const ImpactSetup* impact = std::get_if<ImpactSetup>(&c.setup);
  {
    TomlKeys s = section("run");
    c.run.end_time = s.number("end_time", 0.0, 0.0, inf, true);
    if (!root["run"]["end_time"]) s.fail("end_time", "missing: the simulated end time in s (> 0)");
    c.run.max_steps = static_cast<std::uint64_t>(s.integer("max_steps", 0, 0, int_max));
    const auto g = s.numbers("gravity").value_or(std::vector<double>{0.0, 0.0, 0.0});
    if (g.size() != 3)
      s.fail("gravity", "expected 3 components [gx, gy, gz], got " + std::to_string(g.size()));
    c.run.gravity = {g[0], g[1], g[2]};
    s.finish();
  }
  {
    TomlKeys s = section("kernel");
    const std::string type = s.text("type", "cubic_spline", {"cubic_spline", "wendland_c2"});
    c.kernel = type == "wendland_c2" ? KernelType::wendland_c2 : KernelType::cubic_spline;
    c.smoothing.eta = s.number("eta", c.smoothing.eta, 0.8, 3.0);
    c.smoothing.min_smoothing_length = s.number("min_smoothing_length", 0.0, 0.0, inf);
    // Impacts: h at most 3 eta (m/rho)^(1/3) by default, per particle (integrator.hpp). A particle thrown
    // clear of the target (the ejecta curtain before it leaves the domain) has too few neighbours, and
    // the neighbour-count correction would otherwise grow its h without bound, until the neighbour search
    // and the crater measurement visit every particle for it (measured: 96 ms per search for 2144
    // particles). Relative to the particle's own h, so that it holds for the fine particles of a graded
    // target as for the coarse ones.
    c.smoothing.max_smoothing_length = s.number("max_smoothing_length", inf, 0.0, inf, true);
    c.smoothing.max_smoothing_ratio =
        s.number("max_smoothing_ratio", impact != nullptr ? 3.0 : inf, 1.0, inf);
    c.smoothing.neighbour_band = s.number("neighbour_band", c.smoothing.neighbour_band, 0.0, 1.0, true);
    const std::string density = s.text("density", "continuity", {"continuity", "summation"});
    c.density = density == "summation" ? DensityMethod::summation : DensityMethod::continuity;
    if (c.smoothing.max_smoothing_length < c.smoothing.min_smoothing_length) {
      s.fail("max_smoothing_length", "must not be below kernel.min_smoothing_length");
    }
    s.finish();
  }
  {
    TomlKeys s = section("viscosity");
    auto& v = c.viscosity;
    v.alpha = s.number("alpha", v.alpha, 0.0, 10.0);
    v.beta = s.number("beta", v.beta, 0.0, 20.0);
    // Impacts default to the Morris-Monaghan switch with the Balsara limiter: with a constant alpha = 1
    // the viscosity damps the excavation flow behind the shock within about a millisecond and the crater
    // stays small (measured on the scaled SCI runs, docs/validation.md "Impact craters").
    const std::string sw =
        s.text("switch", impact != nullptr ? "morris_monaghan" : "none", {"none", "morris_monaghan"});
    v.viscosity_switch = sw == "morris_monaghan" ? ViscositySwitch::morris_monaghan : ViscositySwitch::none;
    v.alpha_min = s.number("alpha_min", v.alpha_min, 0.0, 10.0);
    if (v.alpha_min > v.alpha)
      s.fail("alpha_min", "value " + format_number(v.alpha_min) + " exceeds viscosity.alpha");
    v.decay_factor = s.number("decay_factor", v.decay_factor, 0.0, 10.0, true);
    v.epsilon = s.number("epsilon", v.epsilon, 0.0, 1.0, true);
    v.balsara = s.boolean("balsara", impact != nullptr);
    s.finish();
  }
  {
    TomlKeys s = section("artificial_stress");
    c.artificial_stress = s.number("epsilon", c.artificial_stress, 0.0, 1.0);
    s.finish();
  }
  {
    TomlKeys s = section("time_step");
    auto& t = c.time_step;
    t.courant = s.number("courant", t.courant, 0.0, 1.0, true);
    t.acceleration_factor = s.number("acceleration_factor", t.acceleration_factor, 0.0, 1.0, true);
    t.density_change = s.number("density_change", t.density_change, 0.0, 1.0, true);
    t.energy_change = s.number("energy_change", t.energy_change, 0.0, 1.0);
    // Impacts default to the energy limit with u_floor = U^2/400 (1e4 J/kg at 2 km/s): without it the
    // light stand-in projectile's specific energy can change sign within one step (docs/impact_setup.md).
    const double impact_floor =
        impact != nullptr ? impact->impact_speed * impact->impact_speed / 400.0 : t.energy_floor;
    t.energy_floor = s.number("energy_floor", impact_floor, 0.0, inf);
    t.max_step = s.number("max_step", t.max_step, 0.0, inf, true);
    // Impacts default to the velocity-change limit (time_step.hpp: the light stand-in projectile).
    t.velocity_change = s.number("velocity_change", impact != nullptr ? 0.1 : 0.0, 0.0, 1.0);
    // Impacts default to block time steps (8 levels: the finest particles of a graded target step up to 256
    // times per step of the coarsest) when the density is integrated, which block steps need.
    const int block_default = impact != nullptr && c.density == DensityMethod::continuity ? 8 : 0;
    t.block_levels = static_cast<int>(s.integer("block_levels", block_default, 0, 30));
    if (t.block_levels > 0 && c.density == DensityMethod::summation) {
      s.fail("block_levels",
             "block time steps need kernel.density = \"continuity\" (a summed density would "
             "need every neighbour's density at every substep)");
    }
    s.finish();
  }
  {
    TomlKeys s = section("neighbours");
    auto& n = c.neighbours;
    // Block time steps check the lists at every substep: without a skin they would be rebuilt at each.
    n.search.skin = s.number("skin", c.time_step.block_levels > 0 ? 0.1 : n.search.skin, 0.0, 1.0);
    n.sort_interval = static_cast<std::uint64_t>(s.integer("sort_interval", 20, 0, int_max));
    s.finish();
  }
  {
    TomlKeys s = section("output");
    auto& o = c.output;
    o.snapshot_times = s.numbers("snapshot_times").value_or(std::vector<double>{});
    for (std::size_t i = 0; i < o.snapshot_times.size(); ++i) {
      if (o.snapshot_times[i] < 0.0 || (i > 0 && o.snapshot_times[i] <= o.snapshot_times[i - 1])) {
        s.fail("snapshot_times", "element " + std::to_string(i) + " (" + format_number(o.snapshot_times[i]) +
                                     "): times must be >= 0 and strictly ascending");
      }
    }
    o.checkpoint_interval_steps =
        static_cast<std::uint64_t>(s.integer("checkpoint_interval_steps", 0, 0, int_max));
    o.checkpoint_interval_seconds =
        s.number("checkpoint_interval_seconds", o.checkpoint_interval_seconds, 0.0, inf);
    o.conservation_log = s.boolean("conservation_log", true);
    s.finish();
  }
  if (impact != nullptr && root.contains("late_stage")) {
    throw InputError(source +
                     ": table [late_stage] given but problem.setup = \"impact\": use impact.t_transition "
                     "and impact.A_low");
  }
  if (impact == nullptr && root.contains("crater")) {
    throw InputError(source + ": table [crater] is only for problem.setup = \"impact\"");
  }
  {
    TomlKeys s = section("late_stage");
    c.late_stage.transition_time = s.number("t_transition", 0.0, 0.0, inf);
    c.late_stage.A_low = s.number("A_low", c.late_stage.A_low, 0.0, inf, true);
    s.finish();
  }
  {
    TomlKeys s = section("crater");
    auto& k = c.crater;
    k.check_interval = s.number("check_interval", k.check_interval, 0.0, inf);
    k.radius_tolerance = s.number("radius_tolerance", k.radius_tolerance, 0.0, 1.0, true);
    k.kinetic_energy_fraction =
        s.number("kinetic_energy_fraction", k.kinetic_energy_fraction, 0.0, 1.0, true);
    k.window_fraction = s.number("window_fraction", k.window_fraction, 0.0, 1.0, true);
    k.stop_when_grown = s.boolean("stop_when_grown", k.stop_when_grown);
    s.finish();
  }
  return c;
}

SimulationConfig load_simulation_config(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot read configuration file " + path.string());
  std::ostringstream text;
  text << in.rdbuf();
  return parse_simulation_config(text.str(), path.string());
}

}  // namespace craterkit::sph
