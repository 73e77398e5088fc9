#pragma once
// Ideal gas, P = (gamma - 1) rho E, for the validation problems (Sod tube, Sedov blast).
#include <cmath>

#include "craterkit/sph/physics/eos_state.hpp"

namespace craterkit::sph {

struct IdealGas {
  double gamma;  // ratio of specific heats, > 1
};

// c^2 = dP/drho|_E + (P/rho^2) dP/dE = (gamma - 1) E + (gamma - 1)^2 E = gamma (gamma - 1) E.
// A negative specific energy (possible only through integration error) gives c = 0, not NaN.
inline EosState evaluate(const IdealGas& gas, double density, double specific_energy) noexcept {
  const double gm1 = gas.gamma - 1.0;
  const double c2 = gas.gamma * gm1 * specific_energy;
  return EosState{gm1 * density * specific_energy, c2 > 0.0 ? std::sqrt(c2) : 0.0, gm1 * specific_energy,
                  gm1 * density};
}

}  // namespace craterkit::sph
