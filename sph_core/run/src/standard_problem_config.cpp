#include "craterkit/sph/run/standard_problem_config.hpp"

#include <algorithm>
#include <limits>

#include "craterkit/common/format_number.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/sph/physics/late_stage.hpp"

namespace craterkit::sph {

namespace {

constexpr double inf = std::numeric_limits<double>::infinity();

SedovSetup read_sedov(TomlTable t) {
  SedovSetup p;
  p.material = t.text("material", p.material);
  p.particles_per_side = static_cast<int>(t.integer("particles_per_side", p.particles_per_side, 4, 400));
  p.box_size = t.number("box_size", p.box_size, 0.0, inf, true);
  p.density = t.number("density", p.density, 0.0, inf, true);
  p.blast_energy = t.number("blast_energy", p.blast_energy, 0.0, inf, true);
  p.background_energy = t.number("background_energy", p.background_energy, 0.0, inf);
  p.blast_radius = t.number("blast_radius", p.blast_radius, 0.0, 0.25 * p.box_size);
  t.finish();
  return p;
}

SodSetup read_sod(TomlTable t) {
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
  return p;
}

PlateImpactSetup read_plates(TomlTable t) {
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
  return p;
}

}  // namespace

const std::vector<std::string>& standard_problem_names() {
  static const std::vector<std::string> names = {"sedov", "sod", "plates"};
  return names;
}

std::string setup_name(const StandardProblem& problem) {
  return standard_problem_names()[problem.index()];
}

StandardProblemConfig parse_standard_problem_config(TomlTable& root) {
  const std::string setup = read_problem_setup(root, standard_problem_names());
  StandardProblemConfig c;
  if (setup == "sedov") {
    c.problem = read_sedov(root.table("sedov"));
  } else if (setup == "sod") {
    c.problem = read_sod(root.table("sod"));
  } else {
    c.problem = read_plates(root.table("plates"));
  }
  if (root.contains("crater")) {
    throw InputError(root.source() + ": table [crater] is only for problem.setup = \"impact\"");
  }
  {
    TomlTable s = root.table("late_stage");
    c.late_stage.transition_time = s.number("t_transition", c.late_stage.transition_time, 0.0, inf);
    c.late_stage.A_low = s.number("A_low", c.late_stage.A_low, 0.0, inf, true);
    s.finish();
  }
  c.simulation = parse_simulation_config(root, SimulationConfig{});
  root.finish();
  return c;
}

StandardProblemConfig parse_standard_problem_config(const std::string& toml_text, const std::string& source) {
  TomlTable root = TomlTable::parse(toml_text, source);
  return parse_standard_problem_config(root);
}

ProblemSetup build_standard_problem(const StandardProblemConfig& config) {
  const double eta = config.simulation.solver.smoothing.eta;
  const double alpha = config.simulation.solver.viscosity.alpha;
  ProblemSetup problem = std::visit(
      [&](const auto& setup) -> ProblemSetup {
        using Setup = std::decay_t<decltype(setup)>;
        if constexpr (std::is_same_v<Setup, SedovSetup>) return make_sedov(setup, eta, alpha);
        if constexpr (std::is_same_v<Setup, SodSetup>) return make_sod(setup, eta, alpha);
        if constexpr (std::is_same_v<Setup, PlateImpactSetup>) return make_plate_impact(setup, eta, alpha);
      },
      config.problem);
  if (config.late_stage.transition_time > 0.0) {
    problem.late_stage.transition_time = config.late_stage.transition_time;
    problem.late_stage.A_low.assign(problem.materials.size(), config.late_stage.A_low);
    // Fails early (naming the material) for a law without a bulk modulus, e.g. an ideal gas.
    for (const auto& m : problem.materials) (void)late_stage_material(m, config.late_stage.A_low);
  }
  return problem;
}

RunAttributes standard_problem_record(const StandardProblemConfig& config) {
  RunAttributes record;
  record.texts["setup"] = setup_name(config.problem);
  return record;
}

RunSummary run_standard_problem(const StandardProblemConfig& config, const RunOptions& options) {
  return run_simulation(config.simulation, build_standard_problem(config), standard_problem_record(config),
                        options);
}

}  // namespace craterkit::sph
