#pragma once
// The particles a per-particle phase works on: all of them (global time step), or the list of those
// whose step ends now (block time steps, block_time_steps.hpp). A phase loops k over [0, size()) and
// works on particle at(k); with a list the phase leaves every other particle untouched.
#include <cstddef>
#include <cstdint>
#include <span>

namespace craterkit::sph {

class ParticleSelection {
 public:
  // Every particle 0 .. count-1.
  static ParticleSelection all(std::size_t count) { return ParticleSelection(count, {}, true); }
  // The listed particles (ascending indices keep the memory access in curve order).
  static ParticleSelection listed(std::span<const std::uint32_t> indices) {
    return ParticleSelection(indices.size(), indices, false);
  }

  [[nodiscard]] std::size_t size() const { return size_; }
  [[nodiscard]] bool is_all() const { return all_; }
  [[nodiscard]] std::size_t at(std::size_t k) const { return all_ ? k : list_[k]; }

 private:
  ParticleSelection(std::size_t size, std::span<const std::uint32_t> list, bool all)
      : size_(size), list_(list), all_(all) {}
  std::size_t size_;
  std::span<const std::uint32_t> list_;
  bool all_;
};

}  // namespace craterkit::sph
