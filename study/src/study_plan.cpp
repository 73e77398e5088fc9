#include "craterkit/study/study_plan.hpp"

#include <stdlib.h>

#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>
#include <variant>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "craterkit/common/atomic_file.hpp"
#include "craterkit/common/data_catalogue.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/impact/impact_config.hpp"
#include "craterkit/scaling/constant_sets.hpp"
#include "craterkit/sph/io/material_file.hpp"
#include "craterkit/study/material_axes.hpp"
#include "craterkit/study/run_name.hpp"
#include "craterkit/study/toml_document.hpp"

namespace craterkit::study {

namespace {

using json = nlohmann::ordered_json;

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(file.string() + ": cannot be read");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string full(double value) {
  return fmt::format("{:.17g}", value);
}

// A folder for the changed materials while they are checked (sph::load_material reads files); removed
// with everything in it when the plan is done.
class TemporaryFolder {
 public:
  TemporaryFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "craterkit-sweep-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("cannot create a temporary folder");
    path_ = pattern;
  }
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
  ~TemporaryFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

bool is_path_like(const std::string& value) {
  return value.find('/') != std::string::npos || value.ends_with(".toml");
}

// A material given by a relative path is found next to `anchor` (the base or the study file) when it is
// there, else relative to the working folder; the run's configuration then names it by absolute path, since
// the run does not run where the base lies.
void make_material_absolute(TomlDocument& doc, const std::string& key, const std::filesystem::path& anchor) {
  const auto value = doc.text(key);
  if (!value || !is_path_like(*value) || std::filesystem::path(*value).is_absolute()) return;
  const auto beside = (anchor / *value).lexically_normal();
  const auto resolved =
      std::filesystem::exists(beside) ? beside : std::filesystem::absolute(*value).lexically_normal();
  doc.set_text(key, resolved.string());
}

// A table cell for the value at a key: numbers with 17 digits, strings as they are, other values as TOML;
// "" when the key is absent (the default applies).
std::string cell_of(const TomlDocument& doc, const std::string& key) {
  if (!doc.contains(key) || doc.is_table(key)) return "";
  try {
    if (const auto n = doc.number(key)) return full(*n);
  } catch (const InputError&) {
  }
  try {
    if (const auto t = doc.text(key)) return *t;
  } catch (const InputError&) {
  }
  return doc.literal(key).value_or("");
}

// What a run needs of its target material.
struct TargetProperties {
  double reference_density = 0.0, initial_distention = 1.0, cohesion = 0.0, friction = 0.0;
};

TargetProperties target_properties(const sph::Material& m, const std::string& where) {
  TargetProperties t;
  const auto solid = sph::solid_reference(m.eos);
  if (!solid)
    throw InputError(where + ": the target material '" + m.name + "' is a gas: an impact needs a solid");
  t.reference_density = solid->density;
  if (m.porosity) t.initial_distention = m.porosity->crush_curve.initial_distention;
  if (m.strength) {
    if (const auto* lundborg = std::get_if<sph::LundborgStrength>(&*m.strength)) {
      t.cohesion = lundborg->cohesion;
      t.friction = lundborg->friction_coefficient;
    } else if (const auto* mises = std::get_if<sph::VonMisesStrength>(&*m.strength)) {
      t.cohesion = mises->yield_strength;
    }
  }
  return t;
}

std::string describe_values(const std::vector<AxisValue>& values) {
  std::string out;
  for (const auto& v : values) out += (out.empty() ? "" : ", ") + v.key + " = " + v.literal;
  return out.empty() ? "none (the base)" : out;
}

json number_or_null(double v) {
  return std::isfinite(v) ? json(v) : json();
}

json axis_json(const AxisValue& v) {
  if (v.number) return *v.number;
  return v.literal;
}

}  // namespace

std::filesystem::path run_directory(const std::filesystem::path& out, const std::string& name) {
  return out / "runs" / name;
}

namespace {

// What planning one run needs of the study as a whole.
struct PlanContext {
  const StudyPlan& plan;
  const scaling::ScalingLaw& law;
  const TemporaryFolder& scratch;
  std::map<std::string, sph::Material>& loaded_materials;  // unchanged materials, by file
};

// One run being planned: where its messages point, and what its axes leave for the later steps.
struct RunDraft {
  PlannedRun run;
  std::string where;  // "study.toml: grid run cohesion-0.1", "study.toml: runs[2] (cohesion-0.1)"
  TomlDocument config;
  TomlDocument target;  // the target material as the run has it (changed or not)
  bool target_changed = false;
  std::optional<double> spacings;  // the resolution axis
  bool t_transition_axis = false;
  std::map<std::string, std::string> config_cells;  // table cells of the dotted configuration columns
};

std::string value_where(const StudyPlan& plan, const RunSpec& spec, const AxisValue& v) {
  return plan.study.file.string() + ": " + spec.origin + "." + v.key;
}

// The configuration axes of a run: its dotted keys first, so that the named axes see them (projectile_radius
// the projectile density), then the named ones.
void apply_config_axes(const StudyPlan& plan, const RunSpec& spec, RunDraft& d) {
  const impact::ImpactSetup defaults{};
  for (const auto& v : spec.values) {
    if (v.kind != AxisKind::config_key) continue;
    try {
      d.config.set(v.key, v.literal);
    } catch (const InputError& e) {
      throw InputError(value_where(plan, spec, v) + ": " + e.what());
    }
  }
  // The table cells of the configuration keys, as the study gives them (before paths are made absolute).
  for (const auto& column : plan.extra_columns) {
    if (column.find('.') != std::string::npos && !column.starts_with("target.")) {
      d.config_cells[column] = cell_of(d.config, column);
    }
  }
  for (const auto& v : spec.values) {
    try {
      switch (v.kind) {
        case AxisKind::projectile_mass:
          d.config.set_number("impact.projectile_mass", *v.number);
          break;
        case AxisKind::projectile_radius: {
          const double density =
              d.config.number("impact.projectile_density").value_or(defaults.projectile_density);
          d.config.set_number("impact.projectile_mass", projectile_mass(*v.number, density));
          break;
        }
        case AxisKind::impact_speed:
          d.config.set_number("impact.impact_speed", *v.number);
          break;
        case AxisKind::A_low:
          d.config.set_number("impact.A_low", *v.number);
          break;
        case AxisKind::t_transition:
          d.config.set_number("impact.t_transition", *v.number);
          d.t_transition_axis = true;
          break;
        case AxisKind::resolution:
          d.spacings = *v.number;
          break;
        default:
          break;
      }
    } catch (const InputError& e) {
      throw InputError(value_where(plan, spec, v) + ": " + e.what());
    }
  }
  make_material_absolute(d.config, "impact.target_material", plan.study.file.parent_path());
  make_material_absolute(d.config, "impact.projectile_material", plan.study.file.parent_path());
}

// The target material: the run's (base's or axis's), copied and changed when a material axis is given, then
// written next to the run's configuration, which points at it; loaded as the engine loads it to check it.
void plan_target(const PlanContext& ctx, const RunSpec& spec, RunDraft& d) {
  PlannedRun& run = d.run;
  run.target_material =
      d.config.text("impact.target_material").value_or(impact::ImpactSetup{}.target_material);
  std::filesystem::path file;
  try {
    file = resolve_data_set(run.target_material, "materials", "material");
  } catch (const InputError& e) {
    throw InputError(d.where + ": impact.target_material: " + e.what());
  }
  d.target = TomlDocument::parse_file(file);
  d.target_changed =
      apply_material_axes(d.target, spec.values, ctx.plan.study.file.string() + ": " + spec.origin);
  sph::Material material;
  if (d.target_changed) {
    run.target_text = "# Target material of run " + run.name +
                      " (craterkit sweep, docs/sweep.md): " + file.filename().string() +
                      " with the run's material axes.\n" + d.target.dump();
    const auto check_dir = ctx.scratch.path() / std::to_string(run.index);
    std::filesystem::create_directories(check_dir);
    write_text_atomically(check_dir / "target.toml", *run.target_text);
    try {
      material = sph::load_material((check_dir / "target.toml").string());
    } catch (const InputError& e) {
      throw InputError(d.where + ": the target material with this run's axis values (" +
                       describe_values(spec.values) + ") is not valid: " + e.what());
    }
    run.target_material = (run_directory(ctx.plan.out, run.name) / "target.toml").string();
    d.config.set_text("impact.target_material", run.target_material);
  } else {
    const std::string key = file.string();
    if (!ctx.loaded_materials.contains(key)) {
      try {
        ctx.loaded_materials.emplace(key, sph::load_material(key));
      } catch (const InputError& e) {
        throw InputError(d.where + ": impact.target_material: " + e.what());
      }
    }
    material = ctx.loaded_materials.at(key);
  }
  const TargetProperties props = target_properties(material, d.where);
  run.cohesion = props.cohesion;
  run.friction = props.friction;
  run.initial_distention = props.initial_distention;
  run.porosity = 1.0 - 1.0 / props.initial_distention;
  run.bulk_density = props.reference_density / props.initial_distention;
}

// The law's prediction for the run, and the sizing rule applied to its configuration when it is on.
void apply_sizing(const PlanContext& ctx, RunDraft& d) {
  const impact::ImpactSetup defaults{};
  const auto& study = ctx.plan.study;
  PlannedRun& run = d.run;
  SizingInput input;
  try {
    input.projectile_mass = d.config.number("impact.projectile_mass").value_or(defaults.projectile_mass);
    input.projectile_density =
        d.config.number("impact.projectile_density").value_or(defaults.projectile_density);
    input.impact_speed = d.config.number("impact.impact_speed").value_or(defaults.impact_speed);
    input.impact_angle = d.config.number("impact.impact_angle").value_or(defaults.impact_angle);
    const auto g = d.config.numbers("run.gravity").value_or(std::vector<double>{0.0, 0.0, 0.0});
    double g2 = 0.0;
    for (const double c : g) g2 += c * c;
    input.gravity = std::sqrt(g2);
  } catch (const InputError& e) {
    throw InputError(d.where + ": " + e.what());
  }
  input.target_density = run.bulk_density;
  input.strength = study.sizing.predict_with_cohesion ? run.cohesion : 0.0;
  run.sizing = size_run(study.sizing, ctx.law, input, d.spacings);
  if (!study.sizing.enabled) return;
  const auto& s = run.sizing;
  if (!(std::isfinite(s.predicted_crater_radius) && s.predicted_crater_radius > 0.0 &&
        std::isfinite(s.end_time) && s.end_time > 0.0)) {
    throw InputError(d.where +
                     ": the sizing rule needs a finite predicted crater radius and end time; the law " +
                     study.law + " gives R_pred = " + full(s.predicted_crater_radius) + " m and end time " +
                     full(s.end_time) + " s (gravity " + full(input.gravity) + " m/s^2, cohesion " +
                     full(input.strength) + " Pa): set [sizing] enabled = false and size the base by hand");
  }
  if (!(s.inner_spacing < s.particle_spacing)) {
    throw InputError(d.where + ": the sizing rule gives a core spacing dx0 = " + full(s.inner_spacing) +
                     " m not below the outer spacing dx_max = R_pred / n = " + full(s.particle_spacing) +
                     " m: lower sizing.core_spacing_over_projectile_radius or raise the resolution");
  }
  d.config.set_number("impact.domain_radius", s.domain_radius);
  d.config.set_number("impact.particle_spacing", s.particle_spacing);
  d.config.set_number("impact.inner_spacing", s.inner_spacing);
  d.config.set_number("run.end_time", s.end_time);
  if (!d.t_transition_axis) d.config.erase("impact.t_transition");
  run.sized = true;
}

// The inputs of the run's radii.csv row known before it runs, from its parsed configuration.
void fill_table_inputs(const StudyPlan& plan, const impact::ImpactConfig& config, RunDraft& d) {
  PlannedRun& run = d.run;
  const auto& s = config.impact;
  run.impactor_radius = projectile_radius(s.projectile_mass, s.projectile_density);
  run.impactor_density = s.projectile_density;
  run.velocity = s.impact_angle == 0.0 ? s.impact_speed
                                       : s.impact_speed * std::cos(s.impact_angle * std::numbers::pi / 180.0);
  const auto& g = config.simulation.solver.gravity;
  run.gravity = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  run.resolution =
      run.sized ? run.sizing.spacings_across_radius : run.sizing.predicted_crater_radius / s.particle_spacing;
  for (const auto& column : plan.extra_columns) {
    if (column == "A_low") {
      run.extra_cells.push_back(full(s.low_sound_speed_modulus));
    } else if (column == "t_transition") {
      run.extra_cells.push_back(s.transition_time > 0.0 ? full(s.transition_time) : "");
    } else if (column.starts_with("target.")) {
      run.extra_cells.push_back(cell_of(d.target, column.substr(7)));
    } else {
      run.extra_cells.push_back(d.config_cells.at(column));
    }
  }
}

// The columns of radii.csv beyond the fixed ones: A_low, t_transition and the dotted keys that any run
// varies.
std::vector<std::string> extra_columns(const std::vector<RunSpec>& specs) {
  std::vector<std::string> columns;
  for (const auto& spec : specs) {
    for (const auto& v : spec.values) {
      const bool column = v.kind == AxisKind::A_low || v.kind == AxisKind::t_transition ||
                          v.kind == AxisKind::config_key || v.kind == AxisKind::material_key;
      if (column && std::find(columns.begin(), columns.end(), v.key) == columns.end())
        columns.push_back(v.key);
    }
  }
  return columns;
}

}  // namespace

StudyPlan plan_study(const Study& study, const std::filesystem::path& out) {
  StudyPlan plan;
  plan.study = study;
  plan.out = std::filesystem::absolute(out).lexically_normal();
  const std::string source = study.file.string();
  {
    auto folder = plan.out;
    if (folder.filename().empty()) folder = folder.parent_path();
    plan.command =
        "craterkit sweep " + study.file.filename().string() + " --out " + folder.filename().string();
  }

  // The base: an impact configuration, valid as it is.
  const std::string base_text = read_text(study.base);
  try {
    (void)impact::parse_impact_config(base_text, study.base.string());
  } catch (const InputError& e) {
    throw InputError(source + ": study.base: '" + study.base_given + "' (" + study.base.string() +
                     ") is not a valid impact configuration: " + e.what());
  }
  TomlDocument base = TomlDocument::parse(base_text, study.base.string());
  make_material_absolute(base, "impact.target_material", study.base.parent_path());
  make_material_absolute(base, "impact.projectile_material", study.base.parent_path());

  scaling::ScalingLaw law;
  try {
    law = scaling::load_constant_set(study.law).law;
  } catch (const InputError& e) {
    throw InputError(source + ": study.law: " + e.what());
  }

  const std::vector<RunSpec> specs = expand_runs(study);
  plan.extra_columns = extra_columns(specs);
  TemporaryFolder scratch;
  std::map<std::string, sph::Material> loaded_materials;
  const PlanContext ctx{plan, law, scratch, loaded_materials};
  std::map<std::string, std::string> fingerprints;  // configuration and target without the name -> run
  std::map<std::string, std::string> names;         // name -> run

  for (std::size_t k = 0; k < specs.size(); ++k) {
    const RunSpec& spec = specs[k];
    RunDraft d{PlannedRun{}, "", base, base, false, std::nullopt, false, {}};
    PlannedRun& run = d.run;
    run.index = k;
    run.origin = spec.origin;
    run.values = spec.values;
    run.name = run_name(spec.values);
    const std::string label =
        spec.origin == "grid" ? "grid run " + run.name : spec.origin + " (" + run.name + ")";
    d.where = source + ": " + label;
    if (const auto other = names.find(run.name); other != names.end()) {
      throw InputError(d.where + ": its name is that of " + other->second +
                       ": two runs with the same axis values (duplicate runs)");
    }

    d.config.set_text("problem.name", run.name);
    apply_config_axes(plan, spec, d);
    plan_target(ctx, spec, d);
    apply_sizing(ctx, d);

    run.config_text = "# Run " + run.name +
                      " of a craterkit sweep study (docs/sweep.md): the study's base configuration with this "
                      "run's axis values"
                      "\n# and sizing, as run.json records; written by `craterkit sweep`, whose study file "
                      "is the source.\n" +
                      d.config.dump();
    impact::ImpactConfig config;
    try {
      config = impact::parse_impact_config(run.config_text,
                                           (run_directory(plan.out, run.name) / "config.toml").string());
    } catch (const InputError& e) {
      throw InputError(d.where + ": the configuration with this run's axis values (" +
                       describe_values(spec.values) + ") is not valid: " + e.what());
    }

    // Duplicates: the same configuration and target material under another name.
    TomlDocument neutral = d.config;
    neutral.erase("problem.name");
    if (d.target_changed) neutral.set_text("impact.target_material", "<target.toml>");
    const std::string fingerprint = neutral.dump() + "\n--- target ---\n" + run.target_text.value_or("");
    if (const auto other = fingerprints.find(fingerprint); other != fingerprints.end()) {
      throw InputError(d.where + ": the same configuration and target as " + other->second +
                       " (duplicate runs)");
    }
    fingerprints.emplace(fingerprint, label);
    names.emplace(run.name, label);

    fill_table_inputs(plan, config, d);
    plan.runs.push_back(std::move(d.run));
  }
  return plan;
}

std::string run_json(const StudyPlan& plan, const PlannedRun& run) {
  json axes = json::object();
  for (const auto& v : run.values) axes[v.key] = axis_json(v);
  const auto& s = run.sizing;
  const auto& rule = plan.study.sizing;
  json extra = json::object();
  for (std::size_t c = 0; c < plan.extra_columns.size(); ++c)
    extra[plan.extra_columns[c]] = run.extra_cells[c];
  json out = {
      {"name", run.name},
      {"index", run.index},
      {"origin", run.origin},
      {"study", plan.study.name},
      {"axes", axes},
      {"target",
       {{"material", run.target_material},
        {"changed", run.target_text.has_value()},
        {"cohesion", run.cohesion},
        {"friction_coefficient", run.friction},
        {"initial_distention", run.initial_distention},
        {"porosity", run.porosity},
        {"bulk_density", run.bulk_density}}},
      {"sizing",
       {{"applied", run.sized},
        {"law", plan.study.law},
        {"rule",
         {{"predict_with_cohesion", rule.predict_with_cohesion},
          {"domain_over_radius", rule.domain_over_radius},
          {"spacings_across_radius", rule.spacings_across_radius},
          {"core_spacing_over_projectile_radius", rule.core_spacing_over_projectile_radius},
          {"end_time_over_growth_time", rule.end_time_over_growth_time}}},
        {"projectile_radius", number_or_null(s.projectile_radius)},
        {"velocity", number_or_null(s.velocity)},
        {"target_density", number_or_null(run.bulk_density)},
        {"gravity", number_or_null(run.gravity)},
        {"strength", rule.predict_with_cohesion ? run.cohesion : 0.0},
        {"predicted_crater_radius", number_or_null(s.predicted_crater_radius)},
        {"spacings_across_radius", number_or_null(s.spacings_across_radius)},
        {"domain_radius", number_or_null(s.domain_radius)},
        {"particle_spacing", number_or_null(s.particle_spacing)},
        {"inner_spacing", number_or_null(s.inner_spacing)},
        {"end_time", number_or_null(s.end_time)}}},
      {"table",
       {{"impactor_radius", run.impactor_radius},
        {"impactor_density", run.impactor_density},
        {"velocity", run.velocity},
        {"target_density", run.bulk_density},
        {"gravity", run.gravity},
        {"strength", run.cohesion},
        {"friction", run.friction},
        {"porosity", run.porosity},
        {"resolution", number_or_null(run.resolution)},
        {"extra", extra}}},
  };
  return out.dump(2) + "\n";
}

std::string plan_json(const StudyPlan& plan) {
  json runs = json::array();
  for (const auto& run : plan.runs) runs.push_back(run.name);
  json out = {{"study",
               {{"name", plan.study.name},
                {"description", plan.study.description},
                {"file", plan.study.file.string()},
                {"base", plan.study.base.string()},
                {"law", plan.study.law}}},
              {"command", plan.command},
              {"runs", runs},
              {"extra_columns", plan.extra_columns}};
  return out.dump(2) + "\n";
}

namespace {

std::optional<std::string> read_if_exists(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void write_if_different(const std::filesystem::path& file, const std::string& text) {
  if (read_if_exists(file) != text) write_text_atomically(file, text);
}

bool has_started(const std::filesystem::path& dir) {
  for (const char* name : {"attempts.log", "result.json", "failed.json", "checkpoint.h5"}) {
    if (std::filesystem::exists(dir / name)) return true;
  }
  return false;
}

}  // namespace

void write_plan(const StudyPlan& plan, std::optional<std::size_t> only) {
  std::vector<const PlannedRun*> runs;
  for (const auto& run : plan.runs) {
    if (!only || run.index == *only) runs.push_back(&run);
  }
  for (const PlannedRun* planned : runs) {
    const PlannedRun& run = *planned;
    const auto dir = run_directory(plan.out, run.name);
    const auto config = read_if_exists(dir / "config.toml");
    const auto target = read_if_exists(dir / "target.toml");
    const bool differs =
        (config && *config != run.config_text) || (run.target_text && target && *target != *run.target_text);
    if (differs && has_started(dir)) {
      throw InputError(
          dir.string() +
          ": this run has started with another configuration than the study now gives (config.toml or "
          "target.toml differ): the folder belongs to another version of the study; use another --out, "
          "or delete the run's folder to run it again");
    }
  }
  for (const PlannedRun* planned : runs) {
    const PlannedRun& run = *planned;
    const auto dir = run_directory(plan.out, run.name);
    std::filesystem::create_directories(dir);
    if (run.target_text) write_if_different(dir / "target.toml", *run.target_text);
    write_if_different(dir / "config.toml", run.config_text);
    write_if_different(dir / "run.json", run_json(plan, run));
  }
  write_if_different(plan.out / "sweep.json", plan_json(plan));
}

}  // namespace craterkit::study
