#pragma once
// Moving particles between ranks: migration to the rank that owns them after a new split (curve_split.hpp),
// and copies of the particles other ranks need as neighbours (halos). Every field of Particles travels
// (for_each_field, the same list snapshots and checkpoints use), so a field added there is carried too.
//
// Layout of a rank's particles: sorted along the curve by (key, id), the owned particles a contiguous range
// [owned.begin, owned.end), the halos of ranks with lower keys before them and those of ranks with higher
// keys after them. That is the order a serial run holds the same particles in, so a pair loop that sums a
// particle's neighbours in index order (lists sorted by entry, neighbour_search.hpp) adds the same terms in
// the same order as the serial engine: results equal bit for bit.
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "craterkit/sph/domain/communicator.hpp"
#include "craterkit/sph/domain/curve_split.hpp"
#include "craterkit/sph/particles/owned_range.hpp"
#include "craterkit/sph/particles/particles.hpp"

namespace craterkit::sph {

// Sorts the particles and their keys (keys[i] of particle i) along the curve, ties by id: the order migrate()
// leaves and a serial run's curve sort gives. Returns the permutation applied (new index k holds the particle
// that was at order[k]), for values kept beside the particles.
std::vector<std::uint32_t> sort_along_curve(Particles& particles, std::vector<std::uint64_t>& keys);

// Sends every particle to the rank that owns its key (keys[i] of particle i, on the curve of the global
// cube). Afterwards this rank holds exactly the particles of its range, sorted by (key, id), and `keys`
// theirs. Every rank's Particles must hold the same field set (solid_fields). Collective.
void migrate(Particles& particles, std::vector<std::uint64_t>& keys, const KeyRanges& ranges,
             const Communicator& comm);

// Which owned particles each other rank needs: send[q] lists (ascending) the particles of this rank within
// reach of a particle of rank q, where reach means |x_i - x_j| < (1 + skin)(h_i + h_j), the neighbour
// criterion of the search with that skin (neighbour_search.hpp).
struct HaloPlan {
  std::vector<std::vector<std::uint32_t>> send;  // size ranks; send[rank()] is empty
};

// Finds the halos of the owned particles (all of this rank's particles, sorted along the curve) with a
// two-level box test: ranks exchange the bounding box and largest h of their particles, then, with each rank
// within reach, the boxes of the groups within reach of it (consecutive particles along the curve, at most
// `group_size`, no wider than half their largest h), and every particle is tested against the boxes of the
// groups it may reach. Complete: if |x_i - x_j| < (1 + skin)(h_i + h_j), j is in send[owner of i];
// conservative: a few particles are sent that are no neighbour there (a box is wider than its particles).
// period: the box edge along each periodic axis, 0 for an open one (RateOptions::period); distances along a
// periodic axis are minimum-image ones, as in the search. Mirror images need nothing extra: an image is never
// nearer to a particle on the same side of the plane than the particle it reflects. Collective.
[[nodiscard]] HaloPlan find_halos(std::span<const double> x, std::span<const double> y,
                                  std::span<const double> z, std::span<const double> smoothing_length,
                                  double skin, const std::array<double, 3>& period, const Communicator& comm,
                                  std::size_t group_size = 32);

// Adds to `particles` (this rank's owned particles only, sorted along the curve) copies of the particles of
// other ranks that `plan` sends here, in the layout above; `keys` (one per particle) grows with them. Returns
// where the owned particles are now. Collective.
OwnedRange insert_halos(Particles& particles, std::vector<std::uint64_t>& keys, const HaloPlan& plan,
                        const Communicator& comm);

// Sends the current values of the named fields (Particles::for_each_field names, e.g. "x", "density") of the
// particles `plan` sends into the halo copies that insert_halos() made with the same plan: between two pair
// passes of one step only the fields that changed need to travel, not the 347 bytes of a whole particle.
// `owned` is what insert_halos() returned; every rank must name the same fields. Throws std::invalid_argument
// for an unknown field name (on every rank: the names are checked before any exchange). Collective.
void refresh_halos(Particles& particles, const HaloPlan& plan, const OwnedRange& owned,
                   std::span<const std::string_view> fields, const Communicator& comm);

// The same for one value per held particle that is no particle field (e.g. a block time step level): `values`
// holds one per owned and halo particle, in the order insert_halos() left them; every halo takes its owner's.
void refresh_halo_values(std::span<double> values, const HaloPlan& plan, const OwnedRange& owned,
                         const Communicator& comm);

// Every rank's particles (no halos), to rank 0, in rank order: with the ranks' curve ranges, the order of a
// serial run's curve sort. Empty on the other ranks. Collective.
[[nodiscard]] Particles gather_particles(Particles& particles, const std::vector<std::uint64_t>& keys,
                                         const Communicator& comm);

// Removes every particle of this rank that carries `flag` (of particles and keys; the others keep their
// order) and gathers them to rank 0 in rank order: particles that leave the computation, such as ejecta.
// Returns them on rank 0, empty on the others. No halos may be held. Collective.
[[nodiscard]] Particles collect_flagged(Particles& particles, std::vector<std::uint64_t>& keys,
                                        std::uint8_t flag, const Communicator& comm);

// Removes the halos again: only the owned range stays (of particles and keys).
void remove_halos(Particles& particles, std::vector<std::uint64_t>& keys, const OwnedRange& owned);

}  // namespace craterkit::sph
