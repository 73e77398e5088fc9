#include "craterkit/sph/particles/particles.hpp"

#include <cassert>
#include <stdexcept>
#include <type_traits>

namespace craterkit::sph {

namespace {

void set_identity_correction(Particles& p, std::size_t from) {
  for (std::size_t i = from; i < p.size(); ++i)
    p.correction_xx[i] = p.correction_yy[i] = p.correction_zz[i] = 1.0;
}

}  // namespace

void Particles::resize(std::size_t n) {
  const std::size_t old = size();
  for_each_field([n](std::string_view, auto& field) { field.resize(n); });
  for (std::size_t i = old; i < n; ++i) {
    distention[i] = 1.0;
    balsara[i] = 1.0;
    flags[i] = particle_active;
  }
  if (solid_fields) set_identity_correction(*this, old);
}

std::optional<double> Particles::default_for_absent_field(std::string_view name) {
  if (name == "correction_xx" || name == "correction_yy" || name == "correction_zz") return 1.0;
  if (name == "correction_xy" || name == "correction_xz" || name == "correction_yz") return 0.0;
  if (name == "peak_pressure") return 0.0;
  return std::nullopt;
}

void Particles::set_solid_fields(bool present) {
  if (present == solid_fields) return;
  solid_fields = present;
  const std::size_t n = present ? size() : 0;
  for_each_solid_field([n](std::string_view, auto& field) {
    field.assign(n, 0.0);
    field.shrink_to_fit();
  });
  if (present) set_identity_correction(*this, 0);
}

void Particles::reserve(std::size_t n) {
  for_each_field([n](std::string_view, auto& field) { field.reserve(n); });
}

void Particles::shrink_to_fit() {
  for_each_field([](std::string_view, auto& field) { field.shrink_to_fit(); });
}

void Particles::append(const Particles& other) {
  if (other.solid_fields != solid_fields)
    throw std::invalid_argument("Particles::append: the two sets hold different fields (solid_fields)");
  // Field by field, matched by name (a few dozen names: no cost next to the copies).
  for_each_field([&other](std::string_view name, auto& field) {
    using Field = std::decay_t<decltype(field)>;
    other.for_each_field([&](std::string_view other_name, const auto& source) {
      if constexpr (std::is_same_v<std::decay_t<decltype(source)>, Field>) {
        if (other_name == name) field.insert(field.end(), source.begin(), source.end());
      }
    });
  });
}

void Particles::permute(std::span<const std::uint32_t> order) {
  assert(order.size() == size());
  for_each_field([&order](std::string_view, auto& field) {
    auto reordered = field;  // same type and size; one temporary per field, not per particle
    for (std::size_t k = 0; k < order.size(); ++k) reordered[k] = field[order[k]];
    field.swap(reordered);
  });
}

}  // namespace craterkit::sph
