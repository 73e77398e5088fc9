#pragma once
// LAMMPS as a child process: Debian's `lmp` (or $CRATERKIT_LAMMPS) runs an input script craterkit wrote, in
// a folder of its own, serially or under `mpirun -n N`. LAMMPS ends its process on any error of its input,
// so it cannot share craterkit's; a failed run is reported with the ERROR line of its log.
#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace craterkit::dem {

// The LAMMPS executable: $CRATERKIT_LAMMPS if set, else `lmp` on PATH; std::runtime_error saying how to
// install it when there is none.
[[nodiscard]] std::filesystem::path find_lammps();

struct LammpsRun {
  std::filesystem::path folder;  // the script, its log and every file it writes
  std::string script_name;       // input script inside folder
  int processes = 1;             // > 1: under mpirun (Open MPI)
};

// What to do while LAMMPS runs: `call` every `interval`, on the calling thread (to report progress from the
// log, or to look at what LAMMPS has written). An exception from it stops LAMMPS (SIGTERM) and is passed on.
struct LammpsPoll {
  std::function<void()> call;  // empty: just wait
  std::chrono::duration<double> interval{30.0};
};

// Runs the script to its end, the working directory being `folder`. std::runtime_error naming the log and
// quoting its ERROR line (or the exit status) when LAMMPS fails.
void run_lammps(const LammpsRun& run, const LammpsPoll& poll = {});

// The last line of a LAMMPS log that is `columns` numbers (a thermo line of that many columns), or an empty
// vector when there is none yet: to follow a run while it goes (with `thermo_modify flush yes`).
[[nodiscard]] std::vector<double> last_thermo_values(const std::filesystem::path& log, std::size_t columns);

}  // namespace craterkit::dem
