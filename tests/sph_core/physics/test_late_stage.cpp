// Late-stage transition (late_stage.hpp): the switched material has the linear law with c = sqrt(A_low/rho0),
// G scaled by A_low/A (Poisson's ratio kept), strength and porosity kept, and the signal speed (hence the
// time step) scaled by sqrt(A_low/A); the Mach-number helper; the snapshot record.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "craterkit/common/input_error.hpp"
#include "craterkit/sph/io/material_file.hpp"
#include "craterkit/sph/particles/particles.hpp"
#include "craterkit/sph/physics/late_stage.hpp"
#include "craterkit/sph/physics/material.hpp"
#include "craterkit/sph/physics/material_response.hpp"

namespace {
using namespace craterkit::sph;

constexpr double kALow = 2.7e4;  // 0.027 MPa (Jutzi et al. 2022)

double poisson_ratio(double bulk, double shear) {
  return (3.0 * bulk - 2.0 * shear) / (2.0 * (3.0 * bulk + shear));
}

// Longitudinal signal speed of docs/physics.md section 1, c_L^2 = c^2 + (4/3) G/rho.
double signal_speed(const MaterialState& s, double rho) {
  return std::sqrt(s.sound_speed * s.sound_speed + 4.0 / 3.0 * s.shear_modulus / rho);
}

TEST(LateStage, ShippedMaterialsSwitch) {
  for (const char* name : {"basalt_matrix_ryugu", "boulder", "aluminium_projectile", "basalt"}) {
    const Material before = load_material(name);
    const Material after = late_stage_material(before, kALow);
    const auto& till = std::get<Tillotson>(before.eos);
    ASSERT_TRUE(std::holds_alternative<LowSoundSpeed>(after.eos)) << name;
    const auto& law = std::get<LowSoundSpeed>(after.eos);
    EXPECT_EQ(law.reference_density, till.reference_density) << name;
    EXPECT_EQ(law.A, kALow);
    // c = sqrt(A_low / rho0) at any state: 3.2225 m/s for the matrix (rho0 = 2600).
    EXPECT_NEAR(evaluate(after.eos, 0.9 * till.reference_density, 1e6).sound_speed,
                std::sqrt(kALow / till.reference_density), 1e-14);
    // G scaled by A_low/A; Poisson's ratio (bulk modulus A at rho0) unchanged.
    EXPECT_NEAR(after.shear_modulus, before.shear_modulus * kALow / till.A, 1e-12 * after.shear_modulus);
    EXPECT_NEAR(poisson_ratio(kALow, after.shear_modulus), poisson_ratio(till.A, before.shear_modulus),
                1e-12);
    // Strength and porosity kept.
    EXPECT_EQ(after.strength.has_value(), before.strength.has_value());
    EXPECT_EQ(after.porosity.has_value(), before.porosity.has_value());
    EXPECT_EQ(after.name, before.name);
  }
  // 0.027 MPa on the Ryugu matrix: c = sqrt(2.7e4/2600) = 3.22251693317745 m/s (docs/physics.md: about 3
  // m/s).
  EXPECT_NEAR(
      evaluate(late_stage_material(load_material("basalt_matrix_ryugu"), kALow).eos, 2600.0, 0.0).sound_speed,
      3.22251693317745, 1e-13);
  // The projectile's G: 26.7e9 * 2.7e4 / 75.2e9 = 9586.436170212766 Pa.
  EXPECT_NEAR(late_stage_material(load_material("aluminium_projectile"), kALow).shear_modulus,
              9586.436170212766, 1e-9);
}

TEST(LateStage, StrengthAndCrushCurveUnchangedPorousSpeedsScaled) {
  const Material before = load_material("basalt_matrix_ryugu");
  const Material after = late_stage_material(before, kALow);
  const auto& s0 = std::get<LundborgStrength>(*before.strength);
  const auto& s1 = std::get<LundborgStrength>(*after.strength);
  EXPECT_EQ(s1.cohesion, s0.cohesion);
  EXPECT_EQ(s1.friction_coefficient, s0.friction_coefficient);
  EXPECT_EQ(s1.limiting_strength, s0.limiting_strength);
  EXPECT_EQ(s1.weakening_strain, WeakeningStrain::total);
  const auto& p0 = before.porosity->crush_curve;
  const auto& p1 = after.porosity->crush_curve;
  EXPECT_EQ(p1.initial_distention, p0.initial_distention);
  EXPECT_EQ(p1.elastic_pressure, p0.elastic_pressure);
  EXPECT_EQ(p1.solid_pressure, p0.solid_pressure);
  EXPECT_EQ(p1.exponent_1, p0.exponent_1);
  const double speed_factor = std::sqrt(kALow / 26.7e9);
  EXPECT_NEAR(after.porosity->porous_sound_speed, 1500.0 * speed_factor, 1e-12);
  EXPECT_NEAR(after.porosity->matrix_sound_speed, std::sqrt(kALow / 2600.0), 1e-14);
  for (double alpha : {1.0, 1.4, 2.0}) {  // h(alpha) is the same function of alpha before and after
    EXPECT_NEAR(porous_sound_speed_factor(*after.porosity, alpha),
                porous_sound_speed_factor(*before.porosity, alpha), 1e-12);
  }
}

// weakening_strain = "plastic_after_switch" counts the plastic strain from the switch on; the others keep
// theirs.
TEST(LateStage, PlasticAfterSwitchCountsThePlasticStrainFromTheSwitchOn) {
  Material boulder = load_material("boulder");
  for (const auto& [before, after] :
       {std::pair{WeakeningStrain::total, WeakeningStrain::total},
        std::pair{WeakeningStrain::plastic_after_switch, WeakeningStrain::plastic},
        std::pair{WeakeningStrain::plastic, WeakeningStrain::plastic}}) {
    std::get<LundborgStrength>(*boulder.strength).weakening_strain = before;
    const Material switched = late_stage_material(boulder, kALow);
    EXPECT_EQ(std::get<LundborgStrength>(*switched.strength).weakening_strain, after);
  }
}

// At the cold reference state every signal speed, shear term included, scales by sqrt(A_low/A): the time
// step C h / c_L grows by sqrt(A/A_low) = 994.4 for the Ryugu matrix.
TEST(LateStage, SignalSpeedAndTimeStepScaleBySqrtALowOverA) {
  const Material before = load_material("basalt_matrix_ryugu");
  const Material after = late_stage_material(before, kALow);
  for (double alpha : {1.0, 1.5, 2.0}) {
    const double rho = 2600.0 / alpha;
    const double c0 = signal_speed(evaluate_material(before, rho, 0.0, alpha, 0.0), rho);
    const double c1 = signal_speed(evaluate_material(after, rho, 0.0, alpha, 0.0), rho);
    EXPECT_NEAR(c1 / c0, std::sqrt(kALow / 26.7e9), 1e-12) << alpha;
  }
}

// The crush curve still works with the linear matrix: at a state loaded past P_e the consistent
// distention rate uses dP_m/drho_m = A_low/rho0 and dP_m/dE = 0.
TEST(LateStage, CrushCurveKeepsWorkingWithTheLinearMatrix) {
  const Material after = late_stage_material(load_material("basalt_matrix_ryugu"), kALow);
  const auto& crush = after.porosity->crush_curve;
  const double p = 2.0e6;  // between P_e and P_t
  const double alpha = crush_curve_distention(crush, p);
  const double rho = 2600.0 * (1.0 + alpha * p / kALow) / alpha;  // A_low (rho_m/rho0 - 1) = alpha P
  const MaterialState s = evaluate_material(after, rho, 0.0, alpha, 0.0);
  ASSERT_NEAR(s.pressure, p, 1e-6 * p);
  EXPECT_NEAR(s.matrix.dpressure_ddensity, kALow / 2600.0, 1e-12);
  EXPECT_EQ(s.matrix.dpressure_denergy, 0.0);
  EXPECT_LT(distention_rate(crush, alpha, s.pressure, rho, 1.0, 1.0e3, s.matrix),
            0.0);  // compacts when loaded
  EXPECT_EQ(distention_rate(crush, alpha, s.pressure, rho, -1.0, 0.0, s.matrix), 0.0);  // not when unloaded
}

TEST(LateStage, TableAndErrors) {
  const std::vector<Material> table{load_material("basalt_matrix_ryugu"),
                                    load_material("aluminium_projectile")};
  const auto switched = late_stage_materials(table, kALow);
  ASSERT_EQ(switched.size(), 2u);
  EXPECT_EQ(std::get<LowSoundSpeed>(switched[1].eos).reference_density, 2700.0);
  EXPECT_THROW(late_stage_material(table[0], 0.0), craterkit::InputError);
  EXPECT_THROW(late_stage_material(table[0], -1.0), craterkit::InputError);
  try {
    late_stage_material(load_material("ideal_gas_monatomic"), kALow);
    FAIL() << "no error for an ideal gas";
  } catch (const craterkit::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("ideal_gas_monatomic"), std::string::npos) << e.what();
  }
  // Switching twice with the same A_low changes nothing more (A is then A_low).
  const Material twice = late_stage_material(switched[0], kALow);
  EXPECT_EQ(twice.shear_modulus, switched[0].shear_modulus);
}

}  // namespace
