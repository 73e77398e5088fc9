// What this machine gives a two-thread run, measured before timing one (bench/RESULTS.md, "What the second
// processor waits for"): on a virtual machine the two processors may be two cores that share a cache, or
// not, and that changes from day to day. It measures the processors this process is allowed to run on.
//  - throughput: a loop of dependent floating-point operations (no memory traffic) on each processor alone,
//    then on all at once; "together / alone" near 1 means every processor is a whole one;
//  - cache-line round trip: two threads, on the first allowed processor and on another, hand a flag back and
//    forth; what every exchange of data between threads (a barrier, a line written by one and read by the
//    other) costs.
// Usage: bench_machine [ROUNDS]   (ROUNDS of the round trip, default 2,000,000; each figure the median of 5)
#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <thread>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

bool pin_to(int cpu) {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(cpu, &set);
  return pthread_setaffinity_np(pthread_self(), sizeof set, &set) == 0;
}

// Seconds for a fixed chain of multiply-adds that the compiler cannot shorten.
double compute_seconds() {
  const auto start = Clock::now();
  volatile double sink = 0.0;
  double x = 1.0;
  for (long i = 0; i < 400'000'000L; ++i) x = x * 1.0000000001 + 1e-12;
  sink = x;
  (void)sink;
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Mean round trip in ns of a cache line between processors a and b.
double round_trip_ns(int a, int b, long rounds) {
  alignas(64) std::atomic<long> flag{0};
  std::thread other([&] {
    pin_to(b);
    for (long r = 0; r < rounds; ++r) {
      while (flag.load(std::memory_order_acquire) != 2 * r + 1) {
      }
      flag.store(2 * r + 2, std::memory_order_release);
    }
  });
  pin_to(a);
  const auto start = Clock::now();
  for (long r = 0; r < rounds; ++r) {
    flag.store(2 * r + 1, std::memory_order_release);
    while (flag.load(std::memory_order_acquire) != 2 * r + 2) {
    }
  }
  const double ns = std::chrono::duration<double, std::nano>(Clock::now() - start).count();
  other.join();
  return ns / double(rounds);
}

}  // namespace

int main(int argc, char** argv) {
  const long rounds = argc > 1 ? std::atol(argv[1]) : 2'000'000L;
  if (rounds < 1) {
    std::fprintf(stderr, "usage: bench_machine [ROUNDS >= 1]\n");
    return 2;
  }
  // The processors this process may run on (a container or a job's allocation may hold a few of many).
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  std::vector<int> cpus;
  if (sched_getaffinity(0, sizeof allowed, &allowed) == 0) {
    for (int c = 0; c < CPU_SETSIZE; ++c) {
      if (CPU_ISSET(c, &allowed)) cpus.push_back(c);
    }
  }
  if (cpus.empty() || !pin_to(cpus[0])) {
    std::fprintf(stderr, "bench_machine: cannot pin threads to processors here; nothing measured\n");
    return 1;
  }
  std::printf("processors: %zu\n", cpus.size());
  std::vector<double> alone;
  for (const int c : cpus) {
    std::vector<double> runs;
    for (int k = 0; k < 5; ++k) {
      std::thread t([&] {
        pin_to(c);
        runs.push_back(compute_seconds());
      });
      t.join();
    }
    alone.push_back(median(runs));
    std::printf("compute alone on processor %d: %.3f s\n", c, alone.back());
  }
  std::vector<double> together_worst;
  for (int k = 0; k < 5; ++k) {
    std::vector<double> seconds(cpus.size(), 0.0);
    std::vector<std::thread> team;
    for (std::size_t m = 0; m < cpus.size(); ++m) {
      team.emplace_back([&, m] {
        pin_to(cpus[m]);
        seconds[m] = compute_seconds();
      });
    }
    for (auto& t : team) t.join();
    together_worst.push_back(*std::max_element(seconds.begin(), seconds.end()));
  }
  const double slowest_alone = *std::max_element(alone.begin(), alone.end());
  std::printf("compute on all %zu at once: %.3f s (slowest), together / alone %.3f\n", cpus.size(),
              median(together_worst), median(together_worst) / slowest_alone);
  for (std::size_t m = 1; m < cpus.size(); ++m) {
    std::vector<double> trips;
    for (int k = 0; k < 5; ++k) trips.push_back(round_trip_ns(cpus[0], cpus[m], rounds));
    std::printf("cache-line round trip, processors %d and %d: %.0f ns (median of 5; %.0f-%.0f)\n", cpus[0],
                cpus[m], median(trips), *std::min_element(trips.begin(), trips.end()),
                *std::max_element(trips.begin(), trips.end()));
  }
  return 0;
}
