#pragma once
// Mirror (symmetry-plane) boundaries: how a neighbour-list entry names a particle or one of its mirror
// images, and the state of the image as a pair loop must see it (docs/physics.md section 4: a vertical impact
// into a target symmetric about x = 0 and y = 0 runs on the quarter x > 0, y > 0).
//
// A mirror plane x_a = L_a on axis a stands for the missing half of a symmetric system: the particles
// on the other side are the reflections of the real ones. No ghost particles are stored; the neighbour
// search (neighbour_search.hpp) lists the images that lie within reach of a real particle as ordinary
// entries. An entry is a uint32: the low 29 bits the index of the source particle, bit 29 + a set when the
// neighbour is the source reflected across the plane of axis a (up to three axes: the corner image of a
// quarter domain has bits x and y). Hence at most 2^29 particles in a search, with or without mirrors.
//
// The image of particle j across the planes of a set of axes A is the state of a symmetric partner:
//   position   x_a -> 2 L_a - x_a          for a in A
//   velocity   v_a -> -v_a                 for a in A
//   deviatoric stress S_ab -> s_a s_b S_ab, s_a = -1 for a in A else +1: S_xy changes sign under an x- or
//              a y-mirror but not under both, S_xz under x (or z) alone, S_yz under y (or z) alone; the
//              diagonal is unchanged
//   scalars (mass, density, energy, pressure, sound speed, h, viscosity alpha, distention, strain):
//              unchanged.
// A particle near a plane is a neighbour of its own image (the same index with image bits): the pressure
// of its mirror partner is what holds it off the plane.
#include <array>
#include <cstddef>
#include <cstdint>

namespace craterkit::sph {

inline constexpr int mirror_bit_shift = 29;
inline constexpr std::uint32_t neighbour_index_mask = (std::uint32_t{1} << mirror_bit_shift) - 1;
// Largest particle count a neighbour search can index (2^29 = 536,870,912).
inline constexpr std::size_t max_search_particles = std::size_t{neighbour_index_mask} + 1;

[[nodiscard]] constexpr std::uint32_t neighbour_entry(std::uint32_t index, unsigned mirror_bits) noexcept {
  return index | (std::uint32_t(mirror_bits) << mirror_bit_shift);
}
[[nodiscard]] constexpr std::size_t neighbour_index(std::uint32_t entry) noexcept {
  return entry & neighbour_index_mask;
}
// Bit a set: reflected across the plane of axis a; 0 for the particle itself.
[[nodiscard]] constexpr unsigned mirror_bits(std::uint32_t entry) noexcept {
  return entry >> mirror_bit_shift;
}

// The planes x_a = position[a] on the axes with mirrored[a]; what the pair loops need to reflect.
struct MirrorPlanes {
  std::array<bool, 3> mirrored{false, false, false};
  std::array<double, 3> position{0.0, 0.0, 0.0};

  [[nodiscard]] bool any() const { return mirrored[0] || mirrored[1] || mirrored[2]; }
};

// The neighbour named by a list entry, as a pair loop sees it: each component of the real particle's
// state mapped to its image. Written as functions of the loaded value so that, with bits the constant 0
// (runs without mirrors, mirror_image<false>), `x_i - image.position(0, planes, x[j])` is the expression
// `x_i - x[j]` itself and compiles to the same instructions.
struct MirrorImage {
  std::size_t index;
  unsigned bits;

  [[nodiscard]] bool reflected(int axis) const noexcept { return ((bits >> axis) & 1u) != 0; }
  // Position component: 2 L_a - x_a when reflected across the plane of axis a.
  [[nodiscard, gnu::always_inline]] double position(int axis, const MirrorPlanes& planes,
                                                    double x) const noexcept {
    return reflected(axis) ? 2.0 * planes.position[axis] - x : x;
  }
  // Polar-vector component (velocity): -v_a when reflected across the plane of axis a.
  [[nodiscard, gnu::always_inline]] double vector(int axis, double v) const noexcept {
    return reflected(axis) ? -v : v;
  }
  // Off-diagonal component ab (a != b) of a symmetric tensor (deviatoric stress): s_a s_b S_ab, i.e. the
  // sign changes when exactly one of a, b is reflected. The diagonal is invariant.
  [[nodiscard, gnu::always_inline]] double shear(int a, int b, double s) const noexcept {
    return reflected(a) != reflected(b) ? -s : s;
  }
};

// Decodes a list entry. The pair loops are instantiated for mirrored = box.any_mirror(): without mirror
// planes no entry has image bits, the entry is the index and bits is the constant 0, so every reflection
// compiles away and a run without mirrors executes the pair loop it had before mirrors existed (measured:
// bench/RESULTS.md). Lists built with mirror planes must therefore be given to the mirrored instantiation
// (RateOptions::mirror set from the same Box).
template <bool mirrored = true>
[[nodiscard]] constexpr MirrorImage mirror_image(std::uint32_t entry) noexcept {
  if constexpr (mirrored) {
    return {neighbour_index(entry), mirror_bits(entry)};
  } else {
    return {entry, 0u};
  }
}

}  // namespace craterkit::sph
