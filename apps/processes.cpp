#include "processes.hpp"

#include <cstdlib>

#ifdef CRATERKIT_WITH_MPI
#include <array>

#include "craterkit/sph/domain/communicator.hpp"
#include "craterkit/sph/domain/mpi_decomposition.hpp"
#endif

namespace craterkit::cli {

bool launched_by_mpirun() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"}) {
    if (std::getenv(name) != nullptr) return true;
  }
  return false;
}

#ifdef CRATERKIT_WITH_MPI
struct Processes::Session {
  sph::MpiSession mpi;
  Session(int& argc, char**& argv) : mpi(argc, argv) {}
};

namespace {
bool mpi_started = false;
}

Processes::Processes(int& argc, char**& argv) {
  if (!launched_by_mpirun()) return;
  session_ = std::make_unique<Session>(argc, argv);
  mpi_started = true;
}

Processes::~Processes() {
  mpi_started = false;
}

int Processes::rank() {
  return mpi_started ? sph::Communicator::world().rank() : 0;
}
int Processes::count() {
  return mpi_started ? sph::Communicator::world().size() : 1;
}

void Processes::wait_for_all() {
  if (count() < 2) return;
  std::array<double, 1> nothing{0.0};
  sph::Communicator::world().sum(nothing);
}

void Processes::end_all_if_several(int status) {
  if (count() > 1) sph::Communicator::world().abort(status);
}

std::unique_ptr<sph::Decomposition> Processes::decomposition() {
  if (count() < 2) return nullptr;
  return std::make_unique<sph::MpiDecomposition>(sph::Communicator::world());
}
#else
struct Processes::Session {};
Processes::Processes(int&, char**&) {}
Processes::~Processes() = default;
int Processes::rank() {
  return 0;
}
int Processes::count() {
  return 1;
}
void Processes::wait_for_all() {}
void Processes::end_all_if_several(int) {}
std::unique_ptr<sph::Decomposition> Processes::decomposition() {
  return nullptr;
}
#endif

}  // namespace craterkit::cli
