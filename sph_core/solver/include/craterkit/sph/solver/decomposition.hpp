#pragma once
// A run spread over several processes (MPI ranks, docs/parallel.md), as the solver sees it. Each process
// owns a contiguous piece of the space-filling curve and steps its own particles; for the pair passes it
// holds copies of the other processes' particles within reach (halos). The solver calls these operations at
// fixed points of its step and never sees MPI: sph_core/domain implements them (MpiDecomposition), and a
// serial run has no decomposition at all.
//
// Every operation is collective: every process calls it at the same point of the same step.
#include <array>
#include <span>
#include <string_view>

#include "craterkit/sph/particles/owned_range.hpp"
#include "craterkit/sph/particles/particles.hpp"

namespace craterkit::sph {

class Decomposition {
 public:
  virtual ~Decomposition() = default;

  // Keeps this process's share (about 1/size()) of a particle set that every process holds whole, as every
  // process builds the set-up or reads the checkpoint; distribute() then gives each its piece of the curve.
  virtual void take_share(Particles& particles) = 0;

  // Splits the curve anew so that every process gets an equal share of `work` (one value per particle,
  // e.g. its neighbour count) and moves every particle to its owner; afterwards this process holds exactly
  // its own particles, sorted along the curve (the order a serial run's curve sort gives them). No halos may
  // be present.
  virtual void distribute(Particles& particles, std::span<const double> work) = 0;

  // Adds copies (every field) of the particles of other processes within reach of this process's particles:
  // every j with |x_i - x_j| < reach_i + reach_j for an owned i (reach: one length per particle, m, at least
  // its h; (1 + skin) h for a relative skin), mirror images included, minimum images along periodic axes
  // (period: the box edge along each, 0 for an open axis). Returns where the owned particles are now.
  virtual OwnedRange add_halos(Particles& particles, std::span<const double> reach,
                               const std::array<double, 3>& period) = 0;
  // The halo copies take their owners' current values of the named fields (Particles::for_each_field names).
  virtual void refresh_halos(Particles& particles, std::span<const std::string_view> fields) = 0;
  // The same for values that are no particle field (one per owned and halo particle, as add_halos() left
  // them): every halo's value becomes its owner's.
  virtual void refresh_halo_values(std::span<double> values) = 0;
  // Removes the halos: the owned particles are 0 .. size()-1 again.
  virtual void remove_halos(Particles& particles) = 0;

  // Every process's particles (no halos held), to process 0 in curve order: the particle set a serial run
  // would hold, for snapshots and checkpoints. Empty on the other processes.
  [[nodiscard]] virtual Particles gather(Particles& particles) const = 0;

  // Removes this process's particles that carry `flag` (ejecta, which leave the computation; no halos held)
  // and gathers them to process 0, which keeps them from then on: returned there, in process order; empty
  // on the other processes.
  [[nodiscard]] virtual Particles collect_flagged(Particles& particles, std::uint8_t flag) = 0;

  // Element-wise sum and minimum over the processes, in place.
  virtual void sum(std::span<double> values) const = 0;
  virtual void min(std::span<double> values) const = 0;
  // This process and how many there are (rank 0 writes the run's files).
  [[nodiscard]] virtual int rank() const = 0;
  [[nodiscard]] virtual int size() const = 0;
};

}  // namespace craterkit::sph
