// Times the Sedov blast (data/examples/sedov.toml physics, summed density, global step) spread over the ranks
// of mpirun, each with T OpenMP threads: wall time per step, particle updates per second, and where the time
// goes (phases of the solver, "halos" being the halo search, exchange and removal, with the time spent
// waiting for the other processes in them): over several processes the slowest process's share of each phase
// and, in parentheses, the fastest's. With one rank it times the serial engine (no decomposition), the
// reference for the same core count.
//
//   mpirun -n R bench_domain_sedov N [--steps S] [--threads T]
//   e.g. mpirun -n 2 bench_domain_sedov 100 --steps 5 --threads 1   vs   bench_domain_sedov 100 --threads 2
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "craterkit/sph/domain/communicator.hpp"
#include "craterkit/sph/domain/mpi_decomposition.hpp"
#include "craterkit/sph/run/standard_problems.hpp"
#include "craterkit/sph/solver/simulation.hpp"

using namespace craterkit::sph;

int main(int argc, char** argv) {
  MpiSession mpi(argc, argv);
  const Communicator comm = Communicator::world();
  int per_side = 0, steps = 5, threads = 1;
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "--steps" && k + 1 < argc) {
      steps = std::atoi(argv[++k]);
    } else if (arg == "--threads" && k + 1 < argc) {
      threads = std::atoi(argv[++k]);
    } else {
      per_side = std::atoi(arg.c_str());
    }
  }
  if (per_side < 4 || steps < 1 || threads < 1) {
    if (comm.rank() == 0)
      std::fprintf(stderr, "usage: mpirun -n R bench_domain_sedov N [--steps S] [--threads T] (N >= 4)\n");
    return 2;
  }
  omp_set_num_threads(threads);
  SolverParameters solver;
  solver.smoothing.max_smoothing_length = 0.1;
  solver.viscosity.viscosity_switch = ViscositySwitch::morris_monaghan;
  solver.density = DensityMethod::summation;
  SedovSetup setup;
  setup.particles_per_side = per_side;
  setup.blast_radius = 0.1;
  ProblemSetup problem = make_sedov(setup, solver.smoothing.eta, solver.viscosity.alpha);
  const std::size_t particles = problem.particles.size();
  std::unique_ptr<MpiDecomposition> decomposition;
  if (comm.size() > 1) decomposition = std::make_unique<MpiDecomposition>(comm);
  Simulation sim(solver, std::move(problem), decomposition.get());
  const double end_time = 0.05;
  for (int k = 0; k < 2; ++k) sim.step(end_time);  // warm-up (first allocations)
  sim.timers().reset();
  std::array<double, 1> sync{0.0};
  comm.sum(sync);  // start together
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) sim.step(end_time);
  std::array<double, 1> wall{std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
  comm.max(wall);

  // Phases: the slowest rank's time in each (a phase's maximum over the ranks), and the spread of particles.
  std::vector<std::string> names;
  std::vector<double> seconds;
  for (const auto& [name, s] : sim.timers().seconds_by_phase()) {
    names.push_back(name);
    seconds.push_back(s);
  }
  std::vector<double> fastest = seconds;
  comm.max(seconds);
  comm.min(fastest);
  std::array<double, 2> held{double(sim.particles().size()), -double(sim.particles().size())};
  comm.max(std::span(held).first(1));
  comm.min(std::span(held).last(1));
  const double halos = decomposition ? decomposition->halo_fraction() : 0.0;
  if (comm.rank() == 0) {
    std::string phases;
    for (std::size_t k = 0; k < names.size(); ++k) {
      char buffer[96];
      if (comm.size() > 1) {
        std::snprintf(buffer, sizeof buffer, "%s%s %.1f (%.1f)%%", phases.empty() ? "" : ", ",
                      names[k].c_str(), 100.0 * seconds[k] / wall[0], 100.0 * fastest[k] / wall[0]);
      } else {
        std::snprintf(buffer, sizeof buffer, "%s%s %.1f%%", phases.empty() ? "" : ", ", names[k].c_str(),
                      100.0 * seconds[k] / wall[0]);
      }
      phases += buffer;
    }
    std::printf("| %zu | %d x %d | %.3f | %.3g | %.2f | %.0f-%.0f | %s |\n", particles, comm.size(), threads,
                wall[0] / steps, double(particles) * steps / wall[0], halos, -held[1], held[0],
                phases.c_str());
  }
  return 0;
}
