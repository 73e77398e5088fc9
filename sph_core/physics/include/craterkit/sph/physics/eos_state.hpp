#pragma once
// The result of evaluating an equation of state at one (density, specific energy) point.

namespace craterkit::sph {

struct EosState {
  double pressure;            // P, Pa
  double sound_speed;         // c, m/s (floored where the law defines a floor)
  double dpressure_ddensity;  // dP/drho at constant specific energy, m^2/s^2
  double dpressure_denergy;   // dP/dE at constant density, kg/m^3
};

}  // namespace craterkit::sph
