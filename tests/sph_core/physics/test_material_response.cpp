// Per-particle material evaluation (material_response.hpp): porous pressure and sound speed from the
// matrix law, the reduced shear modulus, and strength with weakening and the pressure floor, against
// values computed by hand (mpmath, 30 digits, formulas of docs/physics.md written out independently).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "craterkit/sph/physics/material.hpp"
#include "craterkit/sph/physics/material_response.hpp"

namespace {
using namespace craterkit::sph;

// The Ryugu target as shipped (basalt matrix rho0 = 2600, c_e = 1500 m/s), built here by hand so the
// test does not depend on the data file.
Material ryugu_target(double cohesion) {
  Material m{};
  m.name = "ryugu";
  m.eos = Tillotson{2600.0, 26.7e9, 26.7e9, 487.0e6, 4.72e6, 18.2e6, 0.5, 1.5, 5.0, 5.0, 0.01};
  m.shear_modulus = 22.7e9;
  m.strength = LundborgStrength{cohesion, 0.55, 3.5e9};
  m.porosity = PAlphaPorosity{PAlphaParameters{}, 1500.0, std::sqrt(26.7e9 / 2600.0)};
  return m;
}

// alpha = 1.6, rho = 1700, E = 1e5 J/kg -> matrix rho_m = 2720 (compressed branch). By hand:
//   P_m = (a + b/omega) rho_m E + A chi + B chi^2 = 1833106897.212004 Pa, P = P_m/1.6 = 1145691810.757503 Pa
//   dP_m/drho = 11417187.89052945, dP_m/dE = 5438.469448754636, c_m = 3572.769427668562 m/s
//   h = 1 + 0.6 (1500/3204.564052914338 - 1) = 0.6808494338509195, c = h c_m = 2432.518042108014 m/s
//   G = 22.7e9 h^2 / 1.6 = 6576700062.971982 Pa
TEST(MaterialResponse, PorousPressureSoundSpeedAndShearModulusByHand) {
  const Material m = ryugu_target(0.0);
  const MaterialState s = evaluate_material(m, 1700.0, 1.0e5, 1.6, 0.0);
  EXPECT_NEAR(s.pressure, 1145691810.757503, 1e-6);
  EXPECT_NEAR(s.sound_speed, 2432.518042108014, 1e-9);
  EXPECT_NEAR(s.matrix_sound_speed, 3572.769427668562, 1e-9);  // c_m, for the time step
  EXPECT_NEAR(s.matrix.dpressure_ddensity, 11417187.89052945, 1e-6);
  EXPECT_NEAR(s.matrix.dpressure_denergy, 5438.469448754636, 1e-9);
  EXPECT_NEAR(s.shear_modulus, 6576700062.971982, 1e-3);
  EXPECT_NEAR(porous_sound_speed_factor(*m.porosity, 1.6), 0.6808494338509195, 1e-15);
}

// At the cold reference state (rho_m = rho_m0, E = 0) the sound speed is the linear interpolation
// c = c_s + (alpha - 1)(c_e - c_s)/(alpha0 - 1): c_s at alpha = 1, c_e = 1500 at alpha0 = 2, the
// mean (c_s + c_e)/2 = 2352.282026457169 at alpha = 1.5; and G keeps the matrix's Poisson ratio.
TEST(MaterialResponse, SoundSpeedInterpolatesLinearlyInAlphaAndPoissonRatioIsKept) {
  const Material m = ryugu_target(0.0);
  const double c_s = std::sqrt(26.7e9 / 2600.0);
  const auto poisson = [](double bulk, double shear) {
    return (3 * bulk - 2 * shear) / (2 * (3 * bulk + shear));
  };
  const double matrix_poisson = poisson(26.7e9, 22.7e9);  // K_m = rho0 c_s^2 = A
  for (double alpha : {1.0, 1.25, 1.5, 2.0}) {
    const double rho = 2600.0 / alpha;
    const MaterialState s = evaluate_material(m, rho, 0.0, alpha, 0.0);
    EXPECT_NEAR(s.pressure, 0.0, 1e-6) << alpha;
    EXPECT_NEAR(s.sound_speed, c_s + (alpha - 1.0) * (1500.0 - c_s), 1e-9) << alpha;
    EXPECT_NEAR(poisson(rho * s.sound_speed * s.sound_speed, s.shear_modulus), matrix_poisson, 1e-12)
        << alpha;
  }
  EXPECT_NEAR(evaluate_material(m, 1733.333333333333, 0.0, 1.5, 0.0).sound_speed, 2352.282026457169, 1e-6);
  // Fully compacted: the matrix itself.
  EXPECT_DOUBLE_EQ(evaluate_material(m, 2600.0, 0.0, 1.0, 0.0).shear_modulus, 22.7e9);
}

// Tension in the porous target: alpha = 2, rho = 1200 -> rho_m = 2400 < rho0, cold expanded branch
// (no B chi^2): P_m = A chi = 26.7e9 (2400/2600 - 1) = -1.027e9 Pa, bulk P = -5.135e8 Pa.
TEST(MaterialResponse, TensionIsCutByThePressureFloor) {
  // Cohesionless: no tension at all, P -> 0 and Y = 0.
  const MaterialState loose = evaluate_material(ryugu_target(0.0), 1200.0, 0.0, 2.0, 0.0);
  EXPECT_EQ(loose.pressure, 0.0);
  EXPECT_EQ(loose.yield_strength, 0.0);
  // Y0 = 1e6 Pa weakened by eps_tot = 0.25 to 7.5e5 Pa; f = 0.55 < 1 so P_min = -7.5e5 Pa, where
  // Y = max(0, Y0 + f P) = 7.5e5 (1 - 0.55) = 337500 Pa.
  const MaterialState cohesive = evaluate_material(ryugu_target(1.0e6), 1200.0, 0.0, 2.0, 0.25);
  EXPECT_DOUBLE_EQ(cohesive.pressure, -7.5e5);
  EXPECT_DOUBLE_EQ(cohesive.pressure_floor, -7.5e5);
  EXPECT_NEAR(cohesive.yield_strength, 337500.0, 1e-9);
  // Past unit strain the cohesion is gone: no tension again.
  EXPECT_EQ(evaluate_material(ryugu_target(1.0e6), 1200.0, 0.0, 2.0, 1.5).pressure, 0.0);
  // The unfloored pressure from the law itself, for reference: -5.135e8 Pa.
  EXPECT_NEAR(evaluate_porous(ryugu_target(0.0).eos, *ryugu_target(0.0).porosity, 1200.0, 0.0, 2.0).pressure,
              26.7e9 * (2400.0 / 2600.0 - 1.0) / 2.0, 1e-3);
}

// Compression: Y(1e8 Pa) = Y0 + f P / (1 + f P/(Y_dm - Y0)) = 55148846.37028700 Pa for Y0 = 1e6, f = 0.55.
TEST(MaterialResponse, LundborgAndVonMisesYieldStrength) {
  const std::optional<StrengthModel> lundborg = LundborgStrength{1.0e6, 0.55, 3.5e9};
  const StrengthState s = evaluate_strength(lundborg, 1.0e8, 0.0);
  EXPECT_NEAR(s.yield_strength, 55148846.37028700, 1e-6);
  EXPECT_DOUBLE_EQ(s.pressure_floor, -1.0e6);
  // f > 1: the floor is -Y0/f, which is also where the tension branch reaches zero.
  const std::optional<StrengthModel> steep = LundborgStrength{1.0e6, 2.0, 3.5e9};
  const StrengthState t = evaluate_strength(steep, -1.0e9, 0.0);
  EXPECT_DOUBLE_EQ(t.pressure_floor, -5.0e5);
  EXPECT_EQ(t.yield_strength, 0.0);
  // Von Mises: constant Y, no floor.
  const std::optional<StrengthModel> projectile = VonMisesStrength{0.34e9};
  for (double p : {-1.0e9, 0.0, 5.0e9}) {
    const StrengthState v = evaluate_strength(projectile, p, 3.0);
    EXPECT_EQ(v.yield_strength, 0.34e9);
    EXPECT_EQ(v.pressure_floor, -std::numeric_limits<double>::infinity());
  }
}

TEST(MaterialResponse, NonPorousAndStrengthlessMaterials) {
  Material al{};
  al.eos = Tillotson{2700.0, 75.2e9, 65.0e9, 5.0e6, 3.0e6, 13.9e6, 0.5, 1.63, 5.0, 5.0, 0.01};
  al.shear_modulus = 26.7e9;
  // Strengthless: the law's own state, a fluid (G = 0, Y = 0), tension allowed.
  const EosState law = evaluate(al.eos, 2500.0, 1.0e4);
  const MaterialState fluid = evaluate_material(al, 2500.0, 1.0e4, 1.7 /* ignored */, 0.0);
  EXPECT_EQ(fluid.pressure, law.pressure);
  EXPECT_LT(fluid.pressure, 0.0);
  EXPECT_EQ(fluid.sound_speed, law.sound_speed);
  EXPECT_EQ(fluid.matrix.dpressure_ddensity, law.dpressure_ddensity);
  EXPECT_EQ(fluid.shear_modulus, 0.0);
  EXPECT_EQ(fluid.yield_strength, 0.0);
  // With von Mises strength: the full G, the constant Y, the same (unfloored) pressure.
  al.strength = VonMisesStrength{0.34e9};
  const MaterialState solid = evaluate_material(al, 2500.0, 1.0e4, 1.0, 0.0);
  EXPECT_EQ(solid.pressure, law.pressure);
  EXPECT_EQ(solid.shear_modulus, 26.7e9);
  EXPECT_EQ(solid.yield_strength, 0.34e9);
}

// distention_rate() fed with this header's matrix derivatives: under uniaxial loading at a point on the
// crush curve, alpha falls, and the rate equals the consistent formula of Jutzi et al. (2008) written out.
TEST(MaterialResponse, MatrixDerivativesDriveTheDistentionRate) {
  const Material m = ryugu_target(0.0);
  // A state on the crush curve: choose P = 10 MPa, alpha = alpha_c(P), solve rho for P_m(alpha rho, 0)/alpha
  // = P (cold compressed branch: A chi + B chi^2 = alpha P).
  const double p = 10.0e6;
  const double alpha = crush_curve_distention(m.porosity->crush_curve, p);
  const double chi = (-26.7e9 + std::sqrt(26.7e9 * 26.7e9 + 4 * 26.7e9 * alpha * p)) / (2 * 26.7e9);
  const double rho = 2600.0 * (1.0 + chi) / alpha;
  const MaterialState s = evaluate_material(m, rho, 0.0, alpha, 0.0);
  ASSERT_NEAR(s.pressure, p, 1e-3);
  const double drho = 100.0, de = 0.0;  // kg/m^3/s, W/kg
  const double rate = distention_rate(m.porosity->crush_curve, alpha, s.pressure, rho, drho, de, s.matrix);
  const double slope = crush_curve_slope(m.porosity->crush_curve, p);
  const double dpm_drho = (26.7e9 + 2 * 26.7e9 * chi) / 2600.0;  // E = 0: (A + 2 B chi)/rho0
  const double expected = slope * alpha * drho * dpm_drho / (alpha + slope * (p - rho * dpm_drho));
  EXPECT_LT(rate, 0.0);
  EXPECT_NEAR(rate, expected, 1e-9 * std::abs(expected));
}

// Return to the crush curve: a state left above the curve (alpha0 at 40 MPa, where alpha_c ~ 1.33) is
// put on it at the same rho and E; states on or below the curve are left alone; P >= P_s compacts fully.
TEST(MaterialResponse, ReturnToCrushCurve) {
  const Material m = ryugu_target(0.0);
  const auto& crush = m.porosity->crush_curve;
  const auto bulk_pressure = [&](double rho, double e, double alpha) {
    return evaluate(m.eos, alpha * rho, e).pressure / alpha;
  };
  // rho with P(alpha0) = 40 MPa on the cold branch: A chi + B chi^2 = 2 * 40 MPa.
  const double chi = (-26.7e9 + std::sqrt(26.7e9 * 26.7e9 + 4 * 26.7e9 * 80.0e6)) / (2 * 26.7e9);
  const double rho = 2600.0 * (1.0 + chi) / 2.0;
  for (double e : {0.0, 2.0e4}) {
    ASSERT_GT(2.0, crush_curve_distention(crush, bulk_pressure(rho, e, 2.0)));
    const double a = return_to_crush_curve(m.eos, crush, rho, e, 2.0);
    EXPECT_LT(a, 2.0);
    EXPECT_GT(a, 1.0);
    EXPECT_NEAR(a, crush_curve_distention(crush, bulk_pressure(rho, e, a)), 1e-11) << e;
    // Idempotent: a state on the curve stays.
    EXPECT_NEAR(return_to_crush_curve(m.eos, crush, rho, e, a), a, 1e-12);
  }
  // Below the curve (unloaded after compaction, or elastic): unchanged.
  EXPECT_EQ(return_to_crush_curve(m.eos, crush, 1300.0, 0.0, 2.0), 2.0);  // P = 0 <= P_e
  EXPECT_EQ(return_to_crush_curve(m.eos, crush, 1500.0, 0.0, 1.6), 1.6);  // rho_m = 2400: tension
  // Beyond P_s even when fully compacted: alpha = 1.
  EXPECT_EQ(return_to_crush_curve(m.eos, crush, 2700.0, 0.0, 1.8), 1.0);
}

}  // namespace
