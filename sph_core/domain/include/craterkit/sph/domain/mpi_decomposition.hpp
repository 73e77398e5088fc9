#pragma once
// The solver's Decomposition (solver/decomposition.hpp) over MPI ranks, on the operations of this library:
// distribute() = global curve cube, keys, split_by_work, migrate; add_halos() = find_halos + insert_halos;
// refresh_halos() and remove_halos() with the plan of the last add_halos(). docs/parallel.md.
#include <array>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "craterkit/sph/domain/communicator.hpp"
#include "craterkit/sph/domain/particle_exchange.hpp"
#include "craterkit/sph/solver/decomposition.hpp"

namespace craterkit::sph {

class MpiDecomposition final : public Decomposition {
 public:
  explicit MpiDecomposition(Communicator comm) : comm_(comm) {}

  // Every size()-th particle, from the rank()-th.
  void take_share(Particles& particles) override;
  void distribute(Particles& particles, std::span<const double> work) override;
  OwnedRange add_halos(Particles& particles, std::span<const double> reach,
                       const std::array<double, 3>& period) override;
  void refresh_halos(Particles& particles, std::span<const std::string_view> fields) override;
  void refresh_halo_values(std::span<double> values) override;
  void remove_halos(Particles& particles) override;
  [[nodiscard]] Particles gather(Particles& particles) const override;
  [[nodiscard]] Particles collect_flagged(Particles& particles, std::uint8_t flag) override;
  void sum(std::span<double> values) const override { comm_.sum(values); }
  void min(std::span<double> values) const override { comm_.min(values); }
  [[nodiscard]] int rank() const override { return comm_.rank(); }
  [[nodiscard]] int size() const override { return comm_.size(); }

  // Halo particles per owned particle in the last add_halos(), over all ranks (collective): what the
  // communication costs (bench/RESULTS.md).
  [[nodiscard]] double halo_fraction() const;

 private:
  Communicator comm_;
  std::vector<std::uint64_t> keys_;  // curve key of every held particle (of the last distribute())
  HaloPlan plan_;
  OwnedRange owned_{};
  std::size_t held_ = 0;  // particles held with the halos
};

}  // namespace craterkit::sph
