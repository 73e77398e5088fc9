#include "craterkit/sph/domain/mpi_decomposition.hpp"

#include <array>
#include <stdexcept>

#include "craterkit/sph/domain/curve_split.hpp"
#include "craterkit/sph/particles/space_filling_curve.hpp"

namespace craterkit::sph {

void MpiDecomposition::take_share(Particles& particles) {
  const auto ranks = static_cast<std::size_t>(comm_.size());
  const auto me = static_cast<std::size_t>(comm_.rank());
  std::vector<std::uint32_t> order;
  for (std::size_t i = me; i < particles.size(); i += ranks) order.push_back(static_cast<std::uint32_t>(i));
  const std::size_t kept = order.size();
  for (std::size_t i = 0; i < particles.size(); ++i)
    if (i % ranks != me) order.push_back(static_cast<std::uint32_t>(i));
  particles.permute(order);
  particles.resize(kept);
  keys_.clear();
  held_ = kept;
  owned_ = {0, kept};
}

void MpiDecomposition::distribute(Particles& particles, std::span<const double> work) {
  if (owned_.size() != particles.size() || owned_.begin != 0)
    throw std::logic_error("MpiDecomposition::distribute: halos still held");
  if (work.size() != particles.size())
    throw std::invalid_argument("MpiDecomposition::distribute: one work value per particle needed");
  const CurveCube cube = global_bounding_cube(particles.x, particles.y, particles.z, comm_);
  keys_.resize(particles.size());
  morton_keys(particles.x, particles.y, particles.z, cube, keys_);
  // Sorted here, so that split_by_work sees ascending keys.
  const std::vector<std::uint32_t> order = sort_along_curve(particles, keys_);
  std::vector<double> sorted_work(order.size());
  for (std::size_t k = 0; k < order.size(); ++k) sorted_work[k] = work[order[k]];
  migrate(particles, keys_, split_by_work(keys_, sorted_work, comm_), comm_);
  held_ = particles.size();
  owned_ = {0, held_};
}

OwnedRange MpiDecomposition::add_halos(Particles& particles, std::span<const double> reach,
                                       const std::array<double, 3>& period) {
  if (owned_.size() != particles.size() || owned_.begin != 0 || keys_.size() != particles.size())
    throw std::logic_error("MpiDecomposition::add_halos: halos already held, or distribute() not called");
  if (reach.size() != particles.size())
    throw std::invalid_argument("MpiDecomposition::add_halos: one reach per particle expected");
  // With the reach as the length and no skin, find_halos' criterion is |x_i - x_j| < r_i + r_j.
  plan_ = find_halos(particles.x, particles.y, particles.z, reach, 0.0, period, comm_);
  owned_ = insert_halos(particles, keys_, plan_, comm_);
  held_ = particles.size();
  return owned_;
}

void MpiDecomposition::refresh_halos(Particles& particles, std::span<const std::string_view> fields) {
  if (particles.size() != held_) throw std::logic_error("MpiDecomposition::refresh_halos: no halos held");
  sph::refresh_halos(particles, plan_, owned_, fields, comm_);
}

void MpiDecomposition::refresh_halo_values(std::span<double> values) {
  if (values.size() != held_)
    throw std::logic_error("MpiDecomposition::refresh_halo_values: one value per held particle needed");
  sph::refresh_halo_values(values, plan_, owned_, comm_);
}

void MpiDecomposition::remove_halos(Particles& particles) {
  if (particles.size() != held_) throw std::logic_error("MpiDecomposition::remove_halos: no halos held");
  sph::remove_halos(particles, keys_, owned_);
  held_ = particles.size();
  owned_ = {0, held_};
}

Particles MpiDecomposition::gather(Particles& particles) const {
  if (particles.size() != held_ || owned_.size() != held_)
    throw std::logic_error("MpiDecomposition::gather: halos held, or distribute() not called");
  return gather_particles(particles, keys_, comm_);
}

Particles MpiDecomposition::collect_flagged(Particles& particles, std::uint8_t flag) {
  if (particles.size() != held_ || owned_.size() != held_)
    throw std::logic_error("MpiDecomposition::collect_flagged: halos held, or distribute() not called");
  Particles collected = sph::collect_flagged(particles, keys_, flag, comm_);
  held_ = particles.size();
  owned_ = {0, held_};
  return collected;
}

double MpiDecomposition::halo_fraction() const {
  std::array<double, 2> counts{0.0, 0.0};
  for (const auto& to : plan_.send) counts[0] += static_cast<double>(to.size());
  counts[1] = static_cast<double>(owned_.size());
  comm_.sum(counts);
  return counts[1] > 0.0 ? counts[0] / counts[1] : 0.0;
}

}  // namespace craterkit::sph
