// The late-stage linear law P = A_low (rho/rho0 - 1) (low_sound_speed.hpp) at hand-computed points.
#include <gtest/gtest.h>

#include <cmath>

#include "craterkit/sph/physics/eos.hpp"

namespace {
using namespace craterkit::sph;

// A_low = 0.027 MPa (Jutzi et al. 2022) on the Ryugu matrix density 2600 kg/m^3. By hand:
// c = sqrt(2.7e4 / 2600) = 3.22251693317745 m/s, dP/drho = 2.7e4/2600 = 10.3846153846154 m^2/s^2;
// 2 % compression (rho = 2652): P = 2.7e4 * 0.02 = 540 Pa; 2 % tension (rho = 2548): P = -540 Pa.
const LowSoundSpeed kLaw{2600.0, 2.7e4};

TEST(LowSoundSpeed, HandValues) {
  for (double e : {0.0, 1.0e3, 5.0e6}) {  // energy-free: identical at every E
    const EosState compressed = evaluate(kLaw, 2652.0, e);
    EXPECT_NEAR(compressed.pressure, 540.0, 1e-10);
    EXPECT_NEAR(compressed.sound_speed, 3.22251693317745, 1e-13);
    EXPECT_NEAR(compressed.dpressure_ddensity, 10.3846153846154, 1e-12);
    EXPECT_EQ(compressed.dpressure_denergy, 0.0);
    const EosState stretched = evaluate(kLaw, 2548.0, e);
    EXPECT_NEAR(stretched.pressure, -540.0, 1e-10);
    EXPECT_NEAR(stretched.sound_speed, 3.22251693317745, 1e-13);  // no floor needed: c is constant
  }
  EXPECT_EQ(evaluate(kLaw, 2600.0, 0.0).pressure, 0.0);
}

TEST(LowSoundSpeed, ThroughTheVariantAndConsistentSoundSpeed) {
  const EquationOfState eos = kLaw;
  const EosState s = evaluate(eos, 2700.0, 123.0);
  EXPECT_NEAR(s.pressure, 2.7e4 * (2700.0 / 2600.0 - 1.0), 1e-10);
  // c^2 = dP/drho + (P/rho^2) dP/dE, the definition every law follows.
  EXPECT_NEAR(s.sound_speed * s.sound_speed,
              s.dpressure_ddensity + s.pressure / (2700.0 * 2700.0) * s.dpressure_denergy, 1e-12);
  const auto reference = solid_reference(eos);
  ASSERT_TRUE(reference.has_value());
  EXPECT_EQ(reference->density, 2600.0);
  EXPECT_EQ(reference->bulk_modulus, 2.7e4);
  // A named variant: on a temporary one GCC 12 with -fsanitize=address,undefined takes the solid laws'
  // members in std::visit's other branches for uninitialized (-Wmaybe-uninitialized).
  const EquationOfState gas = IdealGas{1.4};
  EXPECT_FALSE(solid_reference(gas).has_value());
}

}  // namespace
