#pragma once
// The ranks of an MPI job as the engine sees them: who am I, how many are we, and the few collective
// operations the domain decomposition needs (docs/parallel.md). MPI's own types stay in the sources, so a
// program that includes this header needs no MPI headers, and every call checks MPI's return code.
//
// Threads: only the thread that created the MpiSession calls MPI (MPI_THREAD_FUNNELED); the OpenMP threads of
// a rank work between the calls.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace craterkit::sph {

// MPI for the lifetime of the object: initialised at construction, finalised at destruction. One per
// program, created before any Communicator is used.
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

// Bytes for each rank: what a rank sends to (or receives from) every rank, back to back in rank order.
struct RankBytes {
  std::vector<std::byte> bytes;
  std::vector<std::size_t> counts;  // bytes per rank, size() == ranks
};

// MPI_COMM_WORLD. Every member function except rank() and size() is collective: all ranks call it in the
// same order. An MPI error throws std::runtime_error naming the operation.
class Communicator {
 public:
  [[nodiscard]] static Communicator world();

  [[nodiscard]] int rank() const { return rank_; }
  [[nodiscard]] int size() const { return size_; }

  // Element-wise sum, minimum or maximum over the ranks, in place (MPI_Allreduce). The sum of doubles is
  // reduced in rank order by MPI's reduction; bitwise reproducible for a given rank count, not across counts.
  void sum(std::span<double> values) const;
  void min(std::span<double> values) const;
  void max(std::span<double> values) const;
  // True on every rank when it is true on every rank.
  [[nodiscard]] bool all(bool value) const;

  // Every rank's bytes, to every rank (MPI_Allgatherv); counts[r] is what rank r contributed.
  [[nodiscard]] RankBytes all_gather(std::span<const std::byte> bytes) const;
  // Ends every rank of the job with this exit status (MPI_Abort): for a failure that the other ranks, waiting
  // in a collective call, cannot learn of.
  [[noreturn]] void abort(int status) const;
  // Every rank's bytes, to rank 0 (MPI_Gatherv); on the other ranks the result is empty.
  [[nodiscard]] RankBytes gather(std::span<const std::byte> bytes) const;
  // Personalised exchange (MPI_Alltoallv): send.counts[r] bytes go to rank r; the result holds what each rank
  // sent here, in rank order.
  [[nodiscard]] RankBytes all_to_all(const RankBytes& send) const;

 private:
  Communicator(int rank, int size) : rank_(rank), size_(size) {}
  int rank_ = 0;
  int size_ = 1;
};

}  // namespace craterkit::sph
