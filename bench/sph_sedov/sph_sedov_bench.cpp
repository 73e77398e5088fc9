// Times the SPH engine on the Sedov blast (data/examples/sedov.toml physics) at n^3 particles with
// 1 and 2 OpenMP threads: wall time per step, particle updates per second (particles x steps / wall
// second, every phase of a step included), neighbours per particle, bytes per particle, per-phase
// timings and the thread efficiency speedup / threads.
//
//   sph_sedov_bench [n_per_side ...] [--steps S] [--threads T1,T2] [--skin S] [--continuity]
//   e.g. sph_sedov_bench 46 100 --steps 20     (about 1e5 and 1e6 particles)
// Density by kernel summation as in the example; --continuity times the continuity-equation engine that
// the impact runs use (no density pass). The lists are kept with the engine's default skin (0.1);
// --skin 0 rebuilds them at every step.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "craterkit/sph/run/standard_problems.hpp"
#include "craterkit/sph/solver/simulation.hpp"

using namespace craterkit::sph;

namespace {

struct Measurement {
  double seconds_per_step;
  double updates_per_second;
  double neighbours;
  double bytes;
  std::string phases;
};

Measurement measure(int per_side, int threads, int steps, const NeighbourSearchOptions& search,
                    DensityMethod density) {
  omp_set_num_threads(threads);
  SolverParameters solver;
  SedovSetup setup;
  setup.particles_per_side = per_side;
  setup.blast_radius = 0.1;
  const double end_time = 0.05;
  solver.smoothing.max_smoothing_length = 0.1;
  solver.viscosity.viscosity_switch = ViscositySwitch::morris_monaghan;
  solver.density = density;
  solver.neighbours.search = search;
  Simulation sim(solver, make_sedov(setup, solver.smoothing.eta, solver.viscosity.alpha));
  for (int k = 0; k < 2; ++k) sim.step(end_time);  // warm-up (first allocations)
  sim.timers().reset();
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) sim.step(end_time);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  Measurement m;
  m.seconds_per_step = wall / steps;
  m.updates_per_second = static_cast<double>(sim.particles().size()) * steps / wall;
  m.neighbours = sim.mean_neighbours();
  m.bytes = sim.bytes_per_particle();
  for (const auto& [name, seconds] : sim.timers().seconds_by_phase()) {
    char buffer[96];
    std::snprintf(buffer, sizeof buffer, "%s%s %.1f%%", m.phases.empty() ? "" : ", ", name.c_str(),
                  100.0 * seconds / wall);
    m.phases += buffer;
  }
  return m;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> sides;
  int steps = 20;
  std::vector<int> thread_counts = {1, 2};
  NeighbourSearchOptions search = NeighbourParameters{}.search;  // the engine's default skin
  DensityMethod density = DensityMethod::summation;
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "--steps" && k + 1 < argc) {
      steps = std::atoi(argv[++k]);
    } else if (arg == "--skin" && k + 1 < argc) {
      search.skin = std::atof(argv[++k]);
    } else if (arg == "--continuity") {
      density = DensityMethod::continuity;
    } else if (arg == "--threads" && k + 1 < argc) {
      thread_counts.clear();
      std::string list = argv[++k];
      for (std::size_t pos = 0; pos < list.size();) {
        const auto comma = list.find(',', pos);
        thread_counts.push_back(std::atoi(list.substr(pos, comma - pos).c_str()));
        pos = comma == std::string::npos ? list.size() : comma + 1;
      }
    } else if (!arg.empty() && arg.find_first_not_of("0123456789") == std::string::npos) {
      sides.push_back(std::atoi(arg.c_str()));
    } else {
      steps = 0;  // an unknown option or a side that is not a number: the usage below
      break;
    }
  }
  if (sides.empty()) sides = {46, 100};
  const bool sides_valid = std::all_of(sides.begin(), sides.end(), [](int n) { return n >= 2; });
  if (steps < 1 || thread_counts.empty() || !sides_valid) {
    std::fprintf(
        stderr,
        "usage: sph_sedov_bench [n_per_side ...] [--steps S] [--threads 1,2] [--skin S] [--continuity]\n");
    return 2;
  }
  std::printf(
      "| particles | threads | s/step | particle updates/s | neighbours/particle | bytes/particle | "
      "thread efficiency | phases (share of wall time) |\n|---|---|---|---|---|---|---|---|\n");
  for (const int n : sides) {
    double single = 0.0;
    for (const int t : thread_counts) {
      Measurement m;
      try {
        m = measure(n, t, steps, search, density);
      } catch (const std::exception& e) {  // e.g. too few particles per side for the blast radius
        std::fprintf(stderr, "sph_sedov_bench: %d per side: %s\n", n, e.what());
        return 1;
      }
      if (t == thread_counts.front()) single = m.updates_per_second / t;
      std::printf("| %d | %d | %.3f | %.3g | %.1f | %.0f | %.0f %% | %s |\n", n * n * n, t,
                  m.seconds_per_step, m.updates_per_second, m.neighbours, m.bytes,
                  100.0 * m.updates_per_second / (t * single), m.phases.c_str());
      std::fflush(stdout);
    }
  }
  return 0;
}
