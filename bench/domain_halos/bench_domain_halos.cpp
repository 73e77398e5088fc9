// Halo sizes and message counts of the domain decomposition (docs/parallel.md) for a particle file:
//   mpirun -n R bench_domain_halos FILE.h5 [SKIN]
// Every rank reads the file and keeps every R-th particle (not ejected), then the particles are split along
// the curve by work (1 / time_step: a particle costs one update per step of its own, the block time steps'
// measure), migrated, and their halos found with the neighbour search's skin (default 0.1, the engine's with
// block time steps). Prints one line per rank and a summary. Counts, not times: run with more ranks than
// cores
// (--oversubscribe) to see how the halos grow with R.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "craterkit/sph/domain/communicator.hpp"
#include "craterkit/sph/domain/curve_split.hpp"
#include "craterkit/sph/domain/particle_exchange.hpp"
#include "craterkit/sph/io/checkpoint.hpp"

using namespace craterkit::sph;

namespace {

// Every R-th particle that takes part in the hydrodynamics (ejected particles are left out, as by the
// solver).
Particles every_rth(Particles all, const Communicator& comm) {
  std::vector<std::uint32_t> order;
  for (std::size_t i = std::size_t(comm.rank()); i < all.size(); i += std::size_t(comm.size()))
    if (!(all.flags[i] & particle_ejected)) order.push_back(std::uint32_t(i));
  const std::size_t kept = order.size();
  std::vector<char> taken(all.size(), 0);
  for (const auto i : order) taken[i] = 1;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (!taken[i]) order.push_back(std::uint32_t(i));
  all.permute(order);
  all.for_each_field([&](std::string_view, auto& field) { field.resize(kept); });
  return all;
}

std::vector<double> gather_doubles(const std::vector<double>& mine, const Communicator& comm) {
  const RankBytes all = comm.all_gather(std::as_bytes(std::span(mine)));
  std::vector<double> out(all.bytes.size() / sizeof(double));
  if (!out.empty()) std::memcpy(out.data(), all.bytes.data(), all.bytes.size());
  return out;
}

int run(int argc, char** argv) {
  const auto comm = Communicator::world();
  if (argc < 2) {
    if (comm.rank() == 0) std::fprintf(stderr, "usage: mpirun -n R %s FILE.h5 [SKIN]\n", argv[0]);
    return 2;
  }
  const double skin = argc > 2 ? std::stod(argv[2]) : 0.1;
  Particles particles = every_rth(read_checkpoint(argv[1]), comm);
  const CurveCube cube = global_bounding_cube(particles.x, particles.y, particles.z, comm);
  std::vector<std::uint64_t> keys(particles.size());
  morton_keys(particles.x, particles.y, particles.z, cube, keys);
  (void)sort_along_curve(particles, keys);
  const auto work_of = [](const Particles& p) {
    std::vector<double> work(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) work[i] = p.time_step[i] > 0 ? 1.0 / p.time_step[i] : 1.0;
    return work;
  };
  migrate(particles, keys, split_by_work(keys, work_of(particles), comm), comm);
  const std::vector<double> work = work_of(particles);
  const HaloPlan plan = find_halos(particles.x, particles.y, particles.z, particles.smoothing_length, skin,
                                   {0.0, 0.0, 0.0}, comm);
  std::size_t sent = 0, send_messages = 0;
  for (const auto& list : plan.send) {
    sent += list.size();
    send_messages += !list.empty();
  }
  const std::size_t owned_count = particles.size();
  const OwnedRange owned = insert_halos(particles, keys, plan, comm);
  const std::size_t halos = particles.size() - owned.size();
  double my_work = 0.0;
  for (const double w : work) my_work += w;
  std::size_t bytes_per_particle = sizeof(std::uint64_t);
  particles.for_each_field([&](std::string_view, const auto& field) {
    bytes_per_particle += sizeof(typename std::decay_t<decltype(field)>::value_type);
  });

  const std::vector<double> row{double(owned_count), my_work, double(halos), double(sent),
                                double(send_messages)};
  const std::vector<double> rows = gather_doubles(row, comm);
  if (comm.rank() == 0) {
    const std::size_t ranks = std::size_t(comm.size());
    double total_work = 0.0, max_work = 0.0, total_halos = 0.0, total_owned = 0.0, messages = 0.0;
    std::printf("# %s, skin %g, %d ranks, %zu bytes per particle sent (every field)\n", argv[1], skin,
                comm.size(), bytes_per_particle);
    std::printf("rank owned work_share halos halos/owned messages_sent\n");
    for (std::size_t r = 0; r < ranks; ++r) {
      const double* v = &rows[5 * r];
      total_owned += v[0];
      total_work += v[1];
      max_work = std::max(max_work, v[1]);
      total_halos += v[2];
      messages += v[4];
    }
    for (std::size_t r = 0; r < ranks; ++r) {
      const double* v = &rows[5 * r];
      std::printf("%zu %.0f %.4f %.0f %.3f %.0f\n", r, v[0], v[1] / total_work, v[2],
                  v[0] > 0 ? v[2] / v[0] : 0.0, v[4]);
    }
    std::printf(
        "summary: particles %.0f, work imbalance (max/mean) %.4f, halos/owned %.3f, messages per rank %.2f\n",
        total_owned, max_work / (total_work / double(ranks)), total_halos / total_owned,
        messages / double(ranks));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  MpiSession mpi(argc, argv);
  try {
    return run(argc, argv);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "bench_domain_halos: %s\n", error.what());
    return 1;
  }
}
