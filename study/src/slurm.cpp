#include "craterkit/study/slurm.hpp"

#include <fmt/format.h>

#include "craterkit/common/atomic_file.hpp"

namespace craterkit::study {

namespace {

// A word for bash: single-quoted, with embedded quotes closed and escaped.
std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string job_name(const std::string& name) {
  std::string out;
  for (const char c : name) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' ||
                    c == '_' || c == '.';
    out += ok ? c : '_';
  }
  return out.empty() ? "craterkit-sweep" : out;
}

}  // namespace

std::string slurm_script(const StudyPlan& plan, const SlurmOptions& options) {
  const auto out = plan.out.string();
  const auto program = shell_quote(options.program.string());
  const auto study = shell_quote(plan.study.file.string());
  const auto dir = shell_quote(out);
  std::string s;
  s += "#!/bin/bash\n";
  s += fmt::format("#SBATCH --job-name={}\n", job_name(plan.study.name));
  s += fmt::format("#SBATCH --array=0-{}\n", plan.runs.size() - 1);
  s += "#SBATCH --ntasks=1\n";
  s += fmt::format("#SBATCH --cpus-per-task={}\n", options.threads);
  // #SBATCH lines are not shell words: a path with blanks cannot be given there, so the logs are named in it
  // as they are.
  s += fmt::format("#SBATCH --output={}/logs/task-%a.out\n", out);
  s += fmt::format("#SBATCH --error={}/logs/task-%a.err\n", out);
  s += fmt::format(
      "#\n"
      "# Study \"{}\" ({} runs), written by `craterkit sweep --emit slurm` (docs/sweep.md, \"Slurm\").\n"
      "# Submit: sbatch {}/sweep.slurm   (add #SBATCH lines for your partition, account and time limit)\n"
      "# Each array task runs one run, claimed as a normal sweep claims it: a task of a run that is "
      "finished\n"
      "# does nothing, an interrupted one resumes. Requeue or resubmit the array to finish interrupted "
      "runs.\n"
      "# After the array, collect the tables (radii.csv, runs.csv):\n"
      "#   {} sweep --collect {}\n"
      "# e.g. sbatch --dependency=afterany:<array job id> --wrap \"{} sweep --collect {}\"\n",
      plan.study.name, plan.runs.size(), out, options.program.string(), out, options.program.string(), out);
  s += "set -euo pipefail\n";
  s += fmt::format(
      "exec {} sweep {} --out {} --task \"$SLURM_ARRAY_TASK_ID\" --threads "
      "\"${{SLURM_CPUS_PER_TASK:-{}}}\"\n",
      program, study, dir, options.threads);
  return s;
}

std::filesystem::path write_slurm_script(const StudyPlan& plan, const SlurmOptions& options) {
  std::filesystem::create_directories(plan.out / "logs");
  const auto path = plan.out / "sweep.slurm";
  write_text_atomically(path, slurm_script(plan, options));
  std::filesystem::permissions(path, std::filesystem::perms::owner_exec | std::filesystem::perms::group_exec,
                               std::filesystem::perm_options::add);
  return path;
}

}  // namespace craterkit::study
