#pragma once
// The study file of `craterkit sweep` (docs/sweep.md): a base impact configuration, the scaling law whose
// prediction sizes each run, the sizing rule, and the runs: the cartesian product of the [grid] axes plus
// explicit [[runs]] entries. Everything is checked here that can be checked without the base configuration
// and the materials (study_plan.hpp checks the rest); errors are craterkit::InputError
// "<study file>: <key>: <what>" naming grid.<axis>, runs[<i>].<axis>, study.<key> or sizing.<key>.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "craterkit/study/axes.hpp"

namespace craterkit::study {

// One axis value of a run.
struct AxisValue {
  std::string key;  // "cohesion", "impact.grading", "target.strength.limiting_strength"
  AxisKind kind = AxisKind::config_key;
  std::string literal;           // the value as TOML text: "0.05", "\"quarter\"", "[0.0, 0.0, -1.0]"
  std::optional<double> number;  // the value when it is a number
};

// The sizing rule (docs/sweep.md, "Sizing"): with R_pred the law's crater radius of the run,
//   impact.domain_radius    = domain_over_radius R_pred
//   impact.particle_spacing = R_pred / n                 (n = spacings_across_radius, or the resolution axis)
//   impact.inner_spacing    = core_spacing_over_projectile_radius a
//   run.end_time            = end_time_over_growth_time sqrt(R_pred / g)
// The defaults reproduce the rule of the shipped examples (docs/impact_setup.md, "Examples"): the SCI run's
// 15 m domain and 0.5 m outer spacing for R_pred = 8.91 m, dx0 = a/2, end time 2 sqrt(R/g).
struct SizingRule {
  bool enabled = true;
  // Whether the prediction takes the run's cohesion as the law's strength Y (else Y = 0, the gravity regime's
  // larger crater: a safe domain when the law's strength term shrinks the crater more than the engine does).
  bool predict_with_cohesion = true;
  double domain_over_radius = 15.0 / 8.91;
  double spacings_across_radius = 8.91 / 0.5;
  double core_spacing_over_projectile_radius = 0.5;
  double end_time_over_growth_time = 2.0;
};

struct GridAxis {
  std::string key;
  AxisKind kind = AxisKind::config_key;
  std::vector<AxisValue> values;
};

// One run to plan: its axis values in study order and where it came from (for messages).
struct RunSpec {
  std::string origin;  // "grid" or "runs[<i>]"
  std::vector<AxisValue> values;
};

struct Study {
  std::filesystem::path file;  // the study file, absolute
  std::string name;            // [study] name (default: the file's stem)
  std::string description;
  std::string base_given;               // [study] base as written
  std::filesystem::path base;           // the base configuration, absolute
  std::string law = "jutzi2022_ryugu";  // shipped scaling constant set (data/scaling/<law>.toml)
  SizingRule sizing;
  std::vector<GridAxis> grid;          // in the order of the file
  std::vector<RunSpec> explicit_runs;  // [[runs]], in the order of the file
};

// Parses a study; `file` names it in messages and anchors relative paths (base).
Study parse_study(const std::string& text, const std::filesystem::path& file);
Study load_study(const std::filesystem::path& file);

// The runs of a study in order: the grid's cartesian product (first axis outermost, so the last axis varies
// fastest), then the explicit runs.
std::vector<RunSpec> expand_runs(const Study& study);

// Where the base configuration is: a name without '/' is a shipped example (data/examples/<name>, with or
// without ".toml") when one exists; otherwise a path relative to the study file's folder.
std::filesystem::path resolve_base(const std::string& base, const std::filesystem::path& study_file);

}  // namespace craterkit::study
