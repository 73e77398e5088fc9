#include "craterkit/sph/domain/communicator.hpp"

#include <mpi.h>

#include <climits>
#include <cstdlib>
#include <numeric>
#include <stdexcept>
#include <string>

namespace craterkit::sph {
namespace {

void check(int code, const char* operation) {
  if (code == MPI_SUCCESS) return;
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  MPI_Error_string(code, text, &length);
  throw std::runtime_error(std::string("MPI: ") + operation +
                           " failed: " + std::string(text, std::size_t(length)));
}

// MPI counts and displacements are int: a message above 2 GiB has to be split, which the domain layer's
// messages (halos and migrations of at most a few million particles) never need.
std::vector<int> to_int(std::span<const std::size_t> counts, const char* operation) {
  std::vector<int> out(counts.size());
  std::size_t total = 0;
  for (std::size_t r = 0; r < counts.size(); ++r) {
    total += counts[r];
    if (total > std::size_t(INT_MAX))
      throw std::runtime_error(std::string("MPI: ") + operation + ": more than 2 GiB in one exchange");
    out[r] = int(counts[r]);
  }
  return out;
}

std::vector<int> displacements(const std::vector<int>& counts) {
  std::vector<int> out(counts.size(), 0);
  if (!counts.empty()) std::exclusive_scan(counts.begin(), counts.end(), out.begin(), 0);
  return out;
}

}  // namespace

MpiSession::MpiSession(int& argc, char**& argv) {
  int provided = 0;
  check(MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  if (provided < MPI_THREAD_FUNNELED) {
    MPI_Finalize();
    throw std::runtime_error(
        "MPI: the library does not support MPI_THREAD_FUNNELED (OpenMP threads in a rank)");
  }
  // Errors come back as codes (check() turns them into exceptions) instead of aborting the job unexplained.
  MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
}

MpiSession::~MpiSession() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}

Communicator Communicator::world() {
  int rank = 0, size = 1;
  check(MPI_Comm_rank(MPI_COMM_WORLD, &rank), "MPI_Comm_rank");
  check(MPI_Comm_size(MPI_COMM_WORLD, &size), "MPI_Comm_size");
  return {rank, size};
}

void Communicator::sum(std::span<double> values) const {
  check(MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD),
        "MPI_Allreduce (sum)");
}

void Communicator::min(std::span<double> values) const {
  check(MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_DOUBLE, MPI_MIN, MPI_COMM_WORLD),
        "MPI_Allreduce (min)");
}

void Communicator::max(std::span<double> values) const {
  check(MPI_Allreduce(MPI_IN_PLACE, values.data(), int(values.size()), MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD),
        "MPI_Allreduce (max)");
}

bool Communicator::all(bool value) const {
  int flag = value ? 1 : 0;
  check(MPI_Allreduce(MPI_IN_PLACE, &flag, 1, MPI_INT, MPI_LAND, MPI_COMM_WORLD), "MPI_Allreduce (and)");
  return flag != 0;
}

RankBytes Communicator::all_gather(std::span<const std::byte> bytes) const {
  const std::uint64_t mine = bytes.size();
  std::vector<std::uint64_t> sizes(std::size_t(size_), 0);
  check(MPI_Allgather(&mine, 1, MPI_UINT64_T, sizes.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD),
        "MPI_Allgather");
  RankBytes out;
  out.counts.assign(sizes.begin(), sizes.end());
  const std::vector<int> counts = to_int(out.counts, "MPI_Allgatherv");
  const std::vector<int> offsets = displacements(counts);
  out.bytes.resize(std::accumulate(out.counts.begin(), out.counts.end(), std::size_t{0}));
  check(MPI_Allgatherv(bytes.data(), int(mine), MPI_BYTE, out.bytes.data(), counts.data(), offsets.data(),
                       MPI_BYTE, MPI_COMM_WORLD),
        "MPI_Allgatherv");
  return out;
}

void Communicator::abort(int status) const {
  MPI_Abort(MPI_COMM_WORLD, status);
  std::exit(status);  // MPI_Abort does not return; if it did, end this rank at least
}

RankBytes Communicator::gather(std::span<const std::byte> bytes) const {
  const std::uint64_t mine = bytes.size();
  std::vector<std::uint64_t> sizes(std::size_t(size_), 0);
  check(MPI_Gather(&mine, 1, MPI_UINT64_T, sizes.data(), 1, MPI_UINT64_T, 0, MPI_COMM_WORLD), "MPI_Gather");
  RankBytes out;
  std::vector<int> counts, offsets;
  if (rank_ == 0) {
    out.counts.assign(sizes.begin(), sizes.end());
    counts = to_int(out.counts, "MPI_Gatherv");
    offsets = displacements(counts);
    out.bytes.resize(std::accumulate(out.counts.begin(), out.counts.end(), std::size_t{0}));
  }
  check(MPI_Gatherv(bytes.data(), int(mine), MPI_BYTE, out.bytes.data(), counts.data(), offsets.data(),
                    MPI_BYTE, 0, MPI_COMM_WORLD),
        "MPI_Gatherv");
  return out;
}

RankBytes Communicator::all_to_all(const RankBytes& send) const {
  if (send.counts.size() != std::size_t(size_))
    throw std::invalid_argument("Communicator::all_to_all: one byte count per rank expected");
  std::vector<std::uint64_t> send_sizes(send.counts.begin(), send.counts.end());
  std::vector<std::uint64_t> receive_sizes(std::size_t(size_), 0);
  check(
      MPI_Alltoall(send_sizes.data(), 1, MPI_UINT64_T, receive_sizes.data(), 1, MPI_UINT64_T, MPI_COMM_WORLD),
      "MPI_Alltoall");
  RankBytes out;
  out.counts.assign(receive_sizes.begin(), receive_sizes.end());
  const std::vector<int> send_counts = to_int(send.counts, "MPI_Alltoallv");
  const std::vector<int> receive_counts = to_int(out.counts, "MPI_Alltoallv");
  const std::vector<int> send_offsets = displacements(send_counts);
  const std::vector<int> receive_offsets = displacements(receive_counts);
  out.bytes.resize(std::accumulate(out.counts.begin(), out.counts.end(), std::size_t{0}));
  check(MPI_Alltoallv(send.bytes.data(), send_counts.data(), send_offsets.data(), MPI_BYTE, out.bytes.data(),
                      receive_counts.data(), receive_offsets.data(), MPI_BYTE, MPI_COMM_WORLD),
        "MPI_Alltoallv");
  return out;
}

}  // namespace craterkit::sph
