#pragma once
// The processes of one distributed simulation when craterkit runs under mpirun (docs/parallel.md): MPI is
// started only then, so every other use of the program (and a build without MPI) is untouched.
#include <memory>

#include "craterkit/sph/solver/decomposition.hpp"

namespace craterkit::cli {

// Whether mpirun (Open MPI's, or a PMI/PMIx launcher such as srun) started this process.
bool launched_by_mpirun();

// MPI for the lifetime of main() when launched by mpirun; nothing otherwise.
class Processes {
 public:
  Processes(int& argc, char**& argv);
  ~Processes();
  Processes(const Processes&) = delete;
  Processes& operator=(const Processes&) = delete;

  [[nodiscard]] static int rank();   // 0 without mpirun
  [[nodiscard]] static int count();  // 1 without mpirun
  // Waits for every process (a no-op for one).
  static void wait_for_all();
  // Ends the whole job with this status when there are several processes (another process may be waiting
  // for this one in a collective call); returns otherwise.
  static void end_all_if_several(int status);
  // The decomposition of a run over the processes; null for one process or without MPI.
  [[nodiscard]] static std::unique_ptr<sph::Decomposition> decomposition();

 private:
  struct Session;
  std::unique_ptr<Session> session_;
};

}  // namespace craterkit::cli
