#pragma once
// Linear, energy-free "low sound speed" law of the late stage of a crater simulation (Raducan et al.
// 2022; docs/physics.md section 3): after the shock has passed, the matrix equation of state is replaced by
//   P_m = A_low (rho_m / rho_m0 - 1),
// whose sound speed c = sqrt(A_low / rho_m0) can be chosen orders of magnitude below the shock-stage
// value (Jutzi et al. 2022 used A_low ~ 0.027 MPa, c ~ 3 m/s), so the time step of the slow granular
// flow that forms the crater grows by the same factor.
#include <cmath>

#include "craterkit/sph/physics/eos_state.hpp"

namespace craterkit::sph {

struct LowSoundSpeed {
  double reference_density;  // rho_m0, kg/m^3 (the matrix reference density of the law it replaces)
  double A;                  // A_low, the bulk modulus at rho_m0, Pa
};

// dP/drho = A/rho0 and dP/dE = 0 everywhere, so c^2 = dP/drho + (P/rho^2) dP/dE = A/rho0 exactly,
// at every density (also in tension) and independent of the specific energy.
inline EosState evaluate(const LowSoundSpeed& law, double density, double /*specific_energy*/) noexcept {
  const double stiffness = law.A / law.reference_density;
  return EosState{law.A * (density / law.reference_density - 1.0), std::sqrt(stiffness), stiffness, 0.0};
}

}  // namespace craterkit::sph
