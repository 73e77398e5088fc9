#pragma once
// The plan of a study: every run's full configuration (config.toml), its target material when a material
// axis changes it (target.toml), its sizing and the inputs of its radii.csv row, all built and checked before
// any run starts. Each configuration is parsed with impact::parse_impact_config and each changed material
// loaded with sph::load_material, so that a bad axis value stops the study up front; errors are InputErrors
// naming the study file and the run's key (grid.cohesion, runs[3].friction, study.base, study.law).
//
// Folder layout (write_plan): DIR/sweep.json (the plan: run names in order, the extra table columns),
// DIR/runs/<name>/{config.toml, target.toml, run.json}; the runs' outputs go into the same folders
// (sweep.hpp).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "craterkit/study/sizing.hpp"
#include "craterkit/study/study_file.hpp"

namespace craterkit::study {

struct PlannedRun {
  std::size_t index = 0;
  std::string name;
  std::string origin;  // "grid" or "runs[<i>]", for messages
  std::vector<AxisValue> values;
  std::string config_text;                 // DIR/runs/<name>/config.toml
  std::optional<std::string> target_text;  // DIR/runs/<name>/target.toml when a material axis changed it
  std::string target_material;             // the material the run uses (name or path)
  Sizing sizing;                           // the prediction, and the sizes applied when `sized`
  bool sized = false;
  // The target as the run has it.
  double cohesion = 0.0;            // Pa (Lundborg cohesion; von Mises yield strength; 0 without strength)
  double friction = 0.0;            // f (0 without a Lundborg strength)
  double initial_distention = 1.0;  // alpha0 (1 without porosity)
  double porosity = 0.0;            // 1 - 1/alpha0
  double bulk_density = 0.0;        // rho0 / alpha0, kg/m^3
  // Inputs of its radii.csv row known before it runs (sweep_tables.hpp adds the crater).
  double impactor_radius = 0.0, impactor_density = 0.0, velocity = 0.0, gravity = 0.0;
  double resolution = 0.0;  // n when sized, else R_pred / particle_spacing
  // One cell per StudyPlan::extra_columns ("" where the configuration leaves the default); the t_transition
  // cell is empty when the default rule applies and is filled from the run's summary.
  std::vector<std::string> extra_cells;
};

struct StudyPlan {
  Study study;
  std::filesystem::path out;  // absolute
  std::vector<std::string>
      extra_columns;  // A_low, t_transition, dotted keys: the varied ones, in study order
  std::vector<PlannedRun> runs;
  std::string command;  // "craterkit sweep <study file name> --out <folder name>", for the tables' headers
};

// Plans every run of the study for the output folder `out` (materials changed by axes are written as
// out/runs/<name>/target.toml, which the configurations name by absolute path). Writes nothing.
StudyPlan plan_study(const Study& study, const std::filesystem::path& out);

std::filesystem::path run_directory(const std::filesystem::path& out, const std::string& name);

// run.json of a run and sweep.json of the plan (deterministic JSON text).
std::string run_json(const StudyPlan& plan, const PlannedRun& run);
std::string plan_json(const StudyPlan& plan);

// Creates DIR/runs/<name>/ with config.toml, target.toml and run.json, and DIR/sweep.json; files whose
// content is already the same are left alone. A run folder that holds another configuration and has started
// (attempts.log, result.json, failed.json or checkpoint.h5) is an InputError, raised before anything is
// written: the folder belongs to another version of the study. With `only`, just that run's folder (and
// sweep.json): what a Slurm array task needs, without every task rereading every run's files.
void write_plan(const StudyPlan& plan, std::optional<std::size_t> only = std::nullopt);

}  // namespace craterkit::study
