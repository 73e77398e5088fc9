// Times the SPH engine on a solid problem: a block of the porous Ryugu target
// (basalt_matrix_ryugu: Tillotson matrix, Lundborg strength, P-alpha porosity) hit by a slab of the
// aluminium projectile (Tillotson, von Mises) at 1 km/s, on an n^3 lattice (n^3 / 8 in the slab), with
// 1 and 2 OpenMP threads. The same lattice, velocities and neighbour count are then run as pure
// hydrodynamics (both materials without strength and porosity, the target at its matrix density), and
// the ratio of the wall time per step of the two is printed: the cost of the solid mechanics (stress
// terms in the pair loop, Randles-Libersky corrected gradient, Jaumann rate, yield, porous pressure,
// crush-curve return, distention rate) at the same particle and neighbour count.
//
//   sph_solid_bench [n_per_side ...] [--steps S] [--threads T1,T2] [--artificial-stress EPSILON]
//   e.g. sph_solid_bench 46 --steps 10     (about 1e5 particles)
// --artificial-stress turns on the artificial stress (artificial_stress.hpp) in the solid problem.
#include <omp.h>

#include <time.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "craterkit/sph/io/material_file.hpp"
#include "craterkit/sph/physics/material.hpp"
#include "craterkit/sph/solver/simulation.hpp"

using namespace craterkit::sph;

namespace {

// Target block z in [0, 7/8 L), projectile slab z in [7/8 L, L) moving at -impact_speed along z; lattice
// spacing dx; all particles at rest in their cold, unloaded state otherwise.
ProblemSetup make_block(int per_side, bool solid) {
  constexpr double dx = 1e-3;
  constexpr double impact_speed = 1000.0;
  constexpr double eta = 1.2;
  ProblemSetup problem;
  Material target = load_material("basalt_matrix_ryugu");
  Material projectile = load_material("aluminium_projectile");
  if (!solid) {
    target.strength.reset();
    target.porosity.reset();
    projectile.strength.reset();
  }
  problem.materials = {target, projectile};
  const double alpha0 = target.porosity ? target.porosity->crush_curve.initial_distention : 1.0;
  const double target_density = std::get<Tillotson>(target.eos).reference_density / alpha0;
  const double projectile_density = std::get<Tillotson>(projectile.eos).reference_density;
  const int slab = per_side / 8;
  auto& p = problem.particles;
  p.set_solid_fields(false);  // the simulation allocates the group when a material needs it
  p.resize(static_cast<std::size_t>(per_side) * per_side * per_side);
  std::size_t k = 0;
  for (int i = 0; i < per_side; ++i) {
    for (int j = 0; j < per_side; ++j) {
      for (int l = 0; l < per_side; ++l, ++k) {
        const bool in_projectile = l >= per_side - slab;
        const double density = in_projectile ? projectile_density : target_density;
        p.id[k] = k;
        p.material[k] = in_projectile ? 1 : 0;
        p.x[k] = (i + 0.5) * dx;
        p.y[k] = (j + 0.5) * dx;
        p.z[k] = (l + 0.5) * dx;
        p.vz[k] = in_projectile ? -impact_speed : 0.0;
        p.mass[k] = density * dx * dx * dx;
        p.density[k] = density;
        p.distention[k] = in_projectile ? 1.0 : alpha0;
        p.smoothing_length[k] = eta * dx;
        p.viscosity_alpha[k] = 1.0;
      }
    }
  }
  problem.box.lower = {0.0, 0.0, 0.0};
  problem.box.upper = {per_side * dx, per_side * dx, per_side * dx};
  return problem;
}

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Measurement {
  double seconds_per_step;
  double cpu_seconds_per_step;  // CPU time of all threads: on a shared machine the 1-thread figure is the
                                // robust one (wall time includes waiting for a core)
  double updates_per_second;
  double neighbours;
  double bytes;
  std::string phases;
};

Measurement measure(int per_side, int threads, int steps, bool solid, double artificial_stress) {
  omp_set_num_threads(threads);
  SolverParameters solver;
  const double end_time = 1.0;
  if (solid) solver.artificial_stress = artificial_stress;
  Simulation sim(solver, make_block(per_side, solid));
  for (int k = 0; k < 2; ++k) sim.step(end_time);  // warm-up (first allocations)
  sim.timers().reset();
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = cpu_seconds();
  for (int k = 0; k < steps; ++k) sim.step(end_time);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  Measurement m;
  m.seconds_per_step = wall / steps;
  m.cpu_seconds_per_step = (cpu_seconds() - cpu_start) / steps;
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
  int steps = 10;
  double artificial_stress = 0.0;
  std::vector<int> thread_counts = {1, 2};
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "--steps" && k + 1 < argc) {
      steps = std::atoi(argv[++k]);
    } else if (arg == "--artificial-stress" && k + 1 < argc) {
      artificial_stress = std::atof(argv[++k]);
    } else if (arg == "--threads" && k + 1 < argc) {
      thread_counts.clear();
      std::string list = argv[++k];
      for (std::size_t pos = 0; pos < list.size();) {
        const auto comma = list.find(',', pos);
        thread_counts.push_back(std::atoi(list.substr(pos, comma - pos).c_str()));
        pos = comma == std::string::npos ? list.size() : comma + 1;
      }
    } else {
      sides.push_back(std::atoi(arg.c_str()));
    }
  }
  if (sides.empty()) sides = {46};
  if (steps < 1 || thread_counts.empty()) {
    std::fprintf(stderr,
                 "usage: sph_solid_bench [n_per_side ...] [--steps S] [--threads 1,2] [--artificial-stress "
                 "EPSILON]\n");
    return 2;
  }
  std::printf(
      "| particles | threads | problem | s/step (wall) | CPU s/step | particle updates/s | "
      "neighbours/particle | bytes/particle | solid/hydro step (wall; CPU) | phases (share of wall time) |\n"
      "|---|---|---|---|---|---|---|---|---|---|\n");
  for (const int n : sides) {
    for (const int t : thread_counts) {
      const auto hydro = measure(n, t, steps, false, 0.0);
      const auto solid = measure(n, t, steps, true, artificial_stress);
      for (const auto* m : {&hydro, &solid}) {
        char ratio[64] = "1";
        if (m == &solid) {
          std::snprintf(ratio, sizeof ratio, "%.2f; %.2f", solid.seconds_per_step / hydro.seconds_per_step,
                        solid.cpu_seconds_per_step / hydro.cpu_seconds_per_step);
        }
        std::printf("| %d | %d | %s | %.3f | %.3f | %.3g | %.1f | %.0f | %s | %s |\n", n * n * n, t,
                    m == &solid ? "solid" : "hydro", m->seconds_per_step, m->cpu_seconds_per_step,
                    m->updates_per_second, m->neighbours, m->bytes, ratio, m->phases.c_str());
      }
      std::fflush(stdout);
    }
  }
  return 0;
}
