#pragma once
// Equations of state: a closed set of laws held in a std::variant, so that the per-particle loop
// resolves the law once per particle (std::visit, inlined) and never through a virtual call.
// Adding a law: a header with its parameter struct and an inline evaluate(), one entry below.
#include <optional>
#include <type_traits>
#include <variant>

#include "craterkit/sph/physics/eos_state.hpp"
#include "craterkit/sph/physics/ideal_gas.hpp"
#include "craterkit/sph/physics/low_sound_speed.hpp"
#include "craterkit/sph/physics/tillotson.hpp"

namespace craterkit::sph {

using EquationOfState = std::variant<IdealGas, Tillotson, LowSoundSpeed>;

inline EosState evaluate(const EquationOfState& eos, double density, double specific_energy) noexcept {
  return std::visit([&](const auto& law) { return evaluate(law, density, specific_energy); }, eos);
}

// The cold, zero-pressure reference state of a solid law: P(rho0, 0) = 0 and dP/drho = A/rho0 there.
struct SolidReference {
  double density;       // rho0, kg/m^3
  double bulk_modulus;  // A, Pa
};

// rho0 and A of a Tillotson or low-sound-speed law; nullopt for an ideal gas, which has neither.
inline std::optional<SolidReference> solid_reference(const EquationOfState& eos) noexcept {
  return std::visit(
      [](const auto& law) -> std::optional<SolidReference> {
        if constexpr (std::is_same_v<std::decay_t<decltype(law)>, IdealGas>) {
          return std::nullopt;
        } else {
          return SolidReference{law.reference_density, law.A};
        }
      },
      eos);
}

}  // namespace craterkit::sph
