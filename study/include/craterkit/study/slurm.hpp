#pragma once
// `craterkit sweep --emit slurm`: a Slurm job-array script, DIR/sweep.slurm, with one array task per run
// (`craterkit sweep STUDY --out DIR --task $SLURM_ARRAY_TASK_ID`), absolute paths, one log per task in
// DIR/logs/, and a comment on collecting the tables after the array (docs/sweep.md, "Slurm").
#include <filesystem>
#include <string>

#include "craterkit/study/study_plan.hpp"

namespace craterkit::study {

struct SlurmOptions {
  std::filesystem::path program;  // the craterkit executable, absolute
  int threads = 1;                // --cpus-per-task
};

std::string slurm_script(const StudyPlan& plan, const SlurmOptions& options);
// Writes DIR/sweep.slurm (atomically) and creates DIR/logs; returns the script's path.
std::filesystem::path write_slurm_script(const StudyPlan& plan, const SlurmOptions& options);

}  // namespace craterkit::study
