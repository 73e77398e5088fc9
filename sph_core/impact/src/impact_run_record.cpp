#include "craterkit/impact/impact_run_record.hpp"

#include <sstream>

#include "craterkit/common/input_error.hpp"

namespace craterkit::impact {

using namespace sph;

namespace {

// The record's numbers, each with its attribute name: one table for writing and reading.
template <class Record>
auto numbers_of(Record& r) {
  using Number = std::conditional_t<std::is_const_v<Record>, const double*, double*>;
  return std::vector<std::pair<const char*, Number>>{
      {"initial_bulk_density", &r.initial_bulk_density},
      {"initial_sound_speed", &r.initial_sound_speed},
      {"particle_spacing", &r.particle_spacing},
      {"inner_spacing", &r.inner_spacing},
      {"grading", &r.grading},
      {"inner_radius", &r.inner_radius},
      {"domain_radius", &r.domain_radius},
      {"fixed_shell_thickness", &r.fixed_shell_thickness},
      {"gravity", &r.gravity},
      {"escape_speed", &r.escape_speed},
      {"projectile_radius", &r.projectile_radius},
      {"projectile_mass", &r.projectile_mass},
      {"projectile_density", &r.projectile_density},
      {"impact_speed", &r.impact_speed},
      {"impact_angle", &r.impact_angle},
      {"coupling_exponent", &r.coupling_exponent},
      {"stand_in_radius", &r.stand_in_radius},
      {"stand_in_density", &r.stand_in_density},
      {"stand_in_mass", &r.stand_in_mass},
      {"stand_in_density_scale", &r.stand_in_density_scale},
      {"t_transition", &r.transition_time},
      {"A_low", &r.A_low},
      {"A_low_projectile", &r.A_low_projectile},
  };
}

std::string boulder_key(const std::string& name, const char* what) {
  return "boulder_" + name + "_" + what;
}

}  // namespace

ImpactRunRecord make_run_record(const ImpactSummary& s, KernelType kernel, const Particles& initial,
                                double A_low_projectile) {
  ImpactRunRecord r;
  r.initial_bulk_density = s.initial_bulk_density;
  r.initial_sound_speed = s.initial_sound_speed;
  r.particle_spacing = s.particle_spacing;
  r.inner_spacing = s.inner_spacing;
  r.grading = s.grading;
  r.inner_radius = s.inner_radius;
  r.far_radius = s.far_radius;
  r.far_spacing = s.far_spacing;
  r.domain_radius = s.domain_radius;
  r.fixed_shell_thickness = s.fixed_shell_thickness;
  r.gravity = s.gravity;
  r.escape_speed = s.escape_speed;
  r.kernel = kernel;
  r.symmetry = s.symmetry;
  for (std::size_t b = 0; b < s.boulder_names.size(); ++b) {
    const std::uint16_t id = s.boulder_material_ids[b];
    const BoulderSpec spec = boulder_from_particles(initial, s.boulder_names[b],
                                                    [&](std::size_t i) { return initial.material[i] == id; });
    r.boulders.push_back({s.boulder_names[b], id, spec.initial_centre});
  }
  r.projectile_radius = s.projectile_radius;
  r.projectile_mass = s.projectile_mass;
  r.projectile_density = s.projectile_density;
  r.impact_speed = s.impact_speed;
  r.impact_angle = s.impact_angle;
  r.projectile_model = s.model;
  r.coupling_exponent = s.coupling_exponent;
  r.stand_in_radius = s.model_radius;
  r.stand_in_density = s.model_density;
  r.stand_in_mass = s.model_mass;
  r.stand_in_density_scale = s.model_density_scale;
  r.transition_time = s.transition_time;
  r.A_low = s.low_sound_speed_modulus;
  r.A_low_projectile = A_low_projectile;
  return r;
}

RunAttributes run_record_attributes(const ImpactRunRecord& r) {
  RunAttributes a;
  for (const auto& [key, value] : numbers_of(r)) a.numbers[key] = *value;
  if (r.far_radius > 0.0) {  // only then: files of runs without it read as before
    a.numbers["far_radius"] = r.far_radius;
    a.numbers["far_spacing"] = r.far_spacing;
  }
  std::string names;
  for (const auto& b : r.boulders) {
    a.numbers[boulder_key(b.name, "material")] = b.material;
    a.numbers[boulder_key(b.name, "centre_x")] = b.initial_centre[0];
    a.numbers[boulder_key(b.name, "centre_y")] = b.initial_centre[1];
    a.numbers[boulder_key(b.name, "centre_z")] = b.initial_centre[2];
    names += (names.empty() ? "" : ",") + b.name;
  }
  if (!r.boulders.empty()) a.texts["boulders"] = names;
  a.texts["setup"] = "impact";
  a.texts["kernel"] = std::string(kernel_name(r.kernel));
  a.texts["symmetry"] = symmetry_name(r.symmetry);
  a.texts["projectile_model"] = projectile_model_name(r.projectile_model);
  return a;
}

bool is_impact_run(const RunAttributes& a) {
  const auto setup = a.texts.find("setup");
  return setup != a.texts.end() && setup->second == "impact";
}

ImpactRunRecord read_run_record(const RunAttributes& a, const std::string& source) {
  ImpactRunRecord r;
  for (const auto& [key, value] : numbers_of(r)) *value = a.number(key, source);
  if (a.numbers.contains("far_radius")) {
    r.far_radius = a.number("far_radius", source);
    r.far_spacing = a.number("far_spacing", source);
  }
  const std::string& kernel = a.text("kernel", source);
  if (kernel != "cubic_spline" && kernel != "wendland_c2") {
    throw InputError(source + ": attribute kernel = \"" + kernel + "\" is not a kernel of craterkit");
  }
  r.kernel = kernel == "wendland_c2" ? KernelType::wendland_c2 : KernelType::cubic_spline;
  r.symmetry = a.text("symmetry", source) == "quarter" ? DomainSymmetry::quarter : DomainSymmetry::full;
  r.projectile_model = a.text("projectile_model", source) == "resolved"
                           ? ProjectileModel::resolved
                           : ProjectileModel::point_source_stand_in;
  if (const auto names = a.texts.find("boulders"); names != a.texts.end()) {
    std::istringstream list(names->second);
    std::string name;
    while (std::getline(list, name, ',')) {
      RecordedBoulder b;
      b.name = name;
      b.material = static_cast<std::uint16_t>(a.number(boulder_key(name, "material"), source));
      b.initial_centre = {a.number(boulder_key(name, "centre_x"), source),
                          a.number(boulder_key(name, "centre_y"), source),
                          a.number(boulder_key(name, "centre_z"), source)};
      r.boulders.push_back(std::move(b));
    }
  } else {
    for (const auto& [key, value] : a.numbers) {
      if (key.starts_with("boulder_") && key.ends_with("_material")) {
        throw InputError(
            source + ": attribute " + key +
            " names a boulder but the file does not record the boulders' initial centres (written "
            "by an older craterkit): give the boulders explicitly (craterkit measure: --boulders FILE.json)");
      }
    }
  }
  return r;
}

CraterMeasurementOptions crater_measurement_options(const ImpactRunRecord& r) {
  CraterMeasurementOptions m;
  m.rho_initial = r.initial_bulk_density;
  m.particle_spacing = r.particle_spacing;
  if (r.graded()) {  // the local spacing of a graded target (graded_spacing.hpp)
    m.inner_spacing = r.inner_spacing;
    m.inner_radius = r.inner_radius;
    m.grading = r.grading;
    m.far_radius = r.far_radius;
    m.far_spacing = r.far_spacing;
  }
  m.kernel = r.kernel;
  m.quarter_symmetric = r.symmetry == DomainSymmetry::quarter;
  for (const auto& b : r.boulders) {
    BoulderSpec spec;
    spec.name = b.name;
    spec.initial_centre = b.initial_centre;
    spec.material = b.material;
    m.boulders.push_back(std::move(spec));
  }
  m.max_radius = r.domain_radius - r.fixed_shell_thickness;
  return m;
}

}  // namespace craterkit::impact
