// Neighbour-list build time (octree), 1e5 and 1e6 particles, 1 and 2 threads, on a jittered
// cubic lattice (h = 1.22 spacing, about 60 neighbours within h_i + h_j) and on the same lattice with 1 % of
// the particles scattered uniformly over a 100x larger volume (ejecta). The input is sorted along the
// space-filling curve first, as the engine keeps it. Results: bench/RESULTS_neighbours.md.
//
//   bench_neighbours --benchmark_filter=... --benchmark_min_time=2
//
// Arguments of each run: particles, layout (0 lattice, 1 scattered, 2 scattered with 10x h,
// 3 scattered plus one particle very far), threads, skin in percent, octree leaf size.
#include <benchmark/benchmark.h>
#include <omp.h>

#include <cmath>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "craterkit/sph/neighbours/neighbour_search.hpp"
#include "craterkit/sph/particles/space_filling_curve.hpp"

namespace {

struct Cloud {
  std::vector<double> x, y, z, h;
};

// layout 0: jittered lattice; 1: 1 % scattered over a 100x larger volume with the same h; 2: the same but
// the scattered particles have a 10x larger h (expanded ejecta, as h = eta (m / rho)^(1/3) would give);
// 3: as 1 plus one particle 1e7 box widths away (bounding cube beyond the 2^21 Morton resolution).
Cloud make_cloud(std::int64_t target, int layout) {
  const bool scattered = layout > 0;
  const int m = int(std::lround(std::cbrt(double(target))));
  const double spacing = 1.0 / m;
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> jitter(-0.05 * spacing, 0.05 * spacing);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double far_edge = std::cbrt(100.0);  // 100x the volume of the unit cube, centred on it
  Cloud c;
  for (int k = 0; k < m; ++k) {
    for (int j = 0; j < m; ++j) {
      for (int i = 0; i < m; ++i) {
        double px = (i + 0.5) * spacing + jitter(rng), py = (j + 0.5) * spacing + jitter(rng),
               pz = (k + 0.5) * spacing + jitter(rng);
        if (scattered && unit(rng) < 0.01) {
          px = 0.5 + far_edge * (unit(rng) - 0.5);
          py = 0.5 + far_edge * (unit(rng) - 0.5);
          pz = 0.5 + far_edge * (unit(rng) - 0.5);
          c.h.push_back((layout == 2 ? 12.2 : 1.22) * spacing);
        } else {
          c.h.push_back(1.22 * spacing);
        }
        c.x.push_back(px);
        c.y.push_back(py);
        c.z.push_back(pz);
      }
    }
  }
  if (layout == 3) c.x[0] = 1e7;
  const auto order = craterkit::sph::curve_order(c.x, c.y, c.z);
  Cloud sorted;
  for (const auto o : order) {
    sorted.x.push_back(c.x[o]);
    sorted.y.push_back(c.y[o]);
    sorted.z.push_back(c.z[o]);
    sorted.h.push_back(c.h[o]);
  }
  return sorted;
}

const Cloud& cloud(std::int64_t n, int layout) {
  static std::map<std::tuple<std::int64_t, int>, Cloud> cache;
  auto [it, fresh] = cache.try_emplace({n, layout});
  if (fresh) it->second = make_cloud(n, layout);
  return it->second;
}

void BM_Build(benchmark::State& state) {
  const Cloud& c = cloud(state.range(0), int(state.range(1)));
  const int threads_before = omp_get_max_threads();
  omp_set_num_threads(int(state.range(2)));
  craterkit::sph::NeighbourSearch search({double(state.range(3)) / 100.0, std::size_t(state.range(4))});
  craterkit::sph::NeighbourLists lists;
  const craterkit::sph::NeighbourInput input{c.x, c.y, c.z, c.h};
  search.build(input, {}, lists);  // warm-up: buffers reach their steady size
  for (auto _ : state) {
    search.build(input, {}, lists);
    benchmark::DoNotOptimize(lists.neighbours.data());
  }
  omp_set_num_threads(threads_before);
  const double n = double(c.x.size());
  state.counters["particles"] = n;
  state.counters["neighbours"] = lists.mean_neighbours();
  state.counters["list_B_per_particle"] = double(lists.bytes()) / n;
  state.counters["work_B_per_particle"] = double(search.workspace_bytes()) / n;
  state.counters["particles_per_s"] = benchmark::Counter(n, benchmark::Counter::kIsIterationInvariantRate);
}

const std::vector<std::string> names{"n", "layout", "threads", "skin_pct", "leaf"};

// 1e5 and 1e6 particles, every layout, 1 and 2 threads.
BENCHMARK(BM_Build)
    ->ArgsProduct({{100000, 1000000}, {0, 1, 2, 3}, {1, 2}, {0}, {64}})
    ->ArgNames(names)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
// Octree leaf size (particles per leaf), then the Verlet skin, on 1 thread.
BENCHMARK(BM_Build)
    ->ArgsProduct({{100000, 1000000}, {0, 2}, {1}, {0}, {8, 16, 32, 128}})
    ->ArgNames(names)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_Build)
    ->ArgsProduct({{1000000}, {0}, {1}, {10, 20}, {64}})
    ->ArgNames(names)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
