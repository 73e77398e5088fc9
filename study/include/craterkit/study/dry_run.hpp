#pragma once
// `craterkit sweep --dry-run`: the plan's runs with their axis values and sizes, and each run's particle
// count from `craterkit simulate CONFIG --dry-run --json` (which builds the set-up, so a run whose set-up
// fails shows its error here). With the sizing rule off the sizes are the run's own, from the same dry run
// (the base configuration with the run's overrides, e.g. a dotted "impact.domain_radius"). Nothing is written
// into the output folder: the configurations are planned into a temporary folder for the counts.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "craterkit/study/study_plan.hpp"

namespace craterkit::study {

struct ParticleCount {
  std::optional<long long> particles;
  // As the run's dry run reports them: an impact's domain radius and outer and inner spacing (m), the end
  // time (s); empty where it reports none.
  std::optional<double> domain_radius, particle_spacing, inner_spacing, end_time;
  std::string error;  // the set-up's error when it failed
};

// One count per run of the study, `jobs` children at a time.
std::vector<ParticleCount> count_particles(const Study& study, const std::filesystem::path& program,
                                           int jobs);

// The listing: a text table, or a JSON array with --json. `counts` may be empty (no counts).
std::string format_dry_run(const StudyPlan& plan, const std::vector<ParticleCount>& counts, bool json);

}  // namespace craterkit::study
