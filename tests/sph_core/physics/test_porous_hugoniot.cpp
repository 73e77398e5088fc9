// The porous (P-alpha) Hugoniot reference of tests/support: against closed forms with a linear matrix
// (any stiffness, and the rigid-matrix crush-up limit), against the solid Hugoniot when alpha0 = 1, the
// jump conditions with the Tillotson basalt matrix, the strong-shock limit of a porous Grueneisen solid,
// and the impedance match with an aluminium plate.
#include <gtest/gtest.h>

#include <cmath>

#include "craterkit/sph/physics/eos.hpp"
#include "craterkit/sph/physics/p_alpha.hpp"
#include "support/hugoniot.hpp"
#include "support/porous_hugoniot.hpp"

namespace {
using namespace craterkit;
using test_support::porous_hugoniot_at_particle_velocity;
using test_support::porous_hugoniot_at_pressure;

constexpr sph::Tillotson kBasaltMatrix{2600.0, 26.7e9, 26.7e9, 487.0e6, 4.72e6, 18.2e6,
                                       0.5,    1.5,    5.0,    5.0,     0.01};
constexpr sph::Tillotson kAluminium{2700.0, 75.2e9, 65.0e9, 5.0e6, 3.0e6, 13.9e6, 0.5, 1.63, 5.0, 5.0, 0.01};
const sph::PAlphaParameters
    kNominal{};  // docs/physics.md: alpha0 = 2, alpha_t = 1.25, P_e/P_t/P_s = 1/68/213 MPa

// Pressures in every part of the crush curve: elastic, first segment, second segment, fully compacted.
constexpr double kPressures[] = {0.5e6, 2.0e6, 10.0e6, 50.0e6, 67.0e6, 100.0e6, 200.0e6, 300.0e6, 1.0e9};

// With an energy-free linear matrix P_m = A (rho_m/rho0 - 1) the Hugoniot is closed-form: from
// alpha P = A (rho_m/rho0 - 1), V = 1/rho = alpha V0 / (1 + alpha P/A) with V0 = 1/rho0, alpha = alpha_c(P),
// and u_p^2 = P (V1 - V), V1 = alpha0 V0.
TEST(PorousHugoniot, LinearMatrixClosedForm) {
  for (double stiffness : {26.7e9, 2.7e6}) {
    const sph::LowSoundSpeed matrix{2600.0, stiffness};
    const double v0 = 1.0 / 2600.0;
    for (double p : kPressures) {
      const double alpha = sph::crush_curve_distention(kNominal, p);
      const double v = alpha * v0 / (1.0 + alpha * p / stiffness);
      const double up = std::sqrt(p * (2.0 * v0 - v));
      const auto h = porous_hugoniot_at_pressure(matrix, kNominal, p);
      EXPECT_NEAR(h.bulk_density, 1.0 / v, 1e-11 / v) << stiffness << " " << p;
      EXPECT_NEAR(h.particle_velocity, up, 1e-10 * up) << stiffness << " " << p;
      EXPECT_EQ(h.distention, alpha);
      // And back from u_p.
      const auto back = porous_hugoniot_at_particle_velocity(matrix, kNominal, up);
      EXPECT_NEAR(back.pressure, p, 1e-9 * p) << stiffness << " " << p;
    }
  }
}

// Crush-up limit (rigid matrix): V = alpha V0, so u_p^2 = P V0 (alpha0 - alpha_c(P)); once fully
// compacted (P >= P_s) the shock is a snowplow, U_s = u_p alpha0/(alpha0 - 1) = 2 u_p and P = rho1 U_s u_p.
TEST(PorousHugoniot, RigidMatrixCrushUpLimit) {
  const sph::LowSoundSpeed rigid{2600.0, 26.7e18};
  for (double p : kPressures) {
    const double alpha = sph::crush_curve_distention(kNominal, p);
    const auto h = porous_hugoniot_at_pressure(rigid, kNominal, p);
    // Elastic states (P <= P_e) do not compact and a rigid matrix does not strain: u_p -> 0, where the
    // volume jump V1 - V ~ 1e-13 V1 is below what double precision resolves; LinearMatrixClosedForm covers
    // them.
    if (p <= kNominal.elastic_pressure) continue;
    EXPECT_NEAR(h.particle_velocity, std::sqrt(p * (2.0 - alpha) / 2600.0), 1e-7 * h.particle_velocity) << p;
    if (p >= kNominal.solid_pressure) {
      EXPECT_NEAR(h.shock_velocity / h.particle_velocity, 2.0, 1e-7) << p;
      EXPECT_NEAR(h.bulk_density, 2600.0, 1e-5) << p;
    }
  }
}

// alpha0 = alpha_t = 1: a non-porous material, whose Hugoniot is the solid one of support/hugoniot.hpp
// (independent code: root in E at given density, then in density).
TEST(PorousHugoniot, FullyDenseLimitIsTheSolidHugoniot) {
  sph::PAlphaParameters dense = kNominal;
  dense.initial_distention = 1.0;
  dense.transition_distention = 1.0;
  for (double up : {50.0, 300.0, 1000.0, 2000.0, 4000.0}) {
    const auto porous = porous_hugoniot_at_particle_velocity(kBasaltMatrix, dense, up);
    const auto solid = test_support::hugoniot_at_particle_velocity(kBasaltMatrix, {2600.0, 0.0}, up);
    EXPECT_NEAR(porous.pressure, solid.pressure, 1e-8 * solid.pressure) << up;
    EXPECT_NEAR(porous.bulk_density, solid.density, 1e-9 * solid.density) << up;
    EXPECT_NEAR(porous.specific_energy, solid.specific_energy, 1e-7 * solid.specific_energy) << up;
    EXPECT_NEAR(porous.shock_velocity, solid.shock_velocity, 1e-7 * solid.shock_velocity) << up;
  }
}

// With the Tillotson basalt matrix: every relation holds at the computed state, evaluated directly.
TEST(PorousHugoniot, TillotsonMatrixStatesSatisfyJumpConditionsAndCrushCurve) {
  const double rho1 = 1300.0;
  EXPECT_EQ(test_support::porous_initial_density(kBasaltMatrix, kNominal), rho1);
  double last_pressure = 0.0;
  for (double up : {5.0, 20.0, 50.0, 100.0, 200.0, 500.0, 1000.0, 2000.0, 3000.0}) {
    const auto h = porous_hugoniot_at_particle_velocity(kBasaltMatrix, kNominal, up);
    EXPECT_NEAR(h.particle_velocity, up, 1e-9 * up);
    EXPECT_EQ(h.distention, sph::crush_curve_distention(kNominal, h.pressure));
    const double matrix_pressure =
        sph::evaluate(kBasaltMatrix, h.distention * h.bulk_density, h.specific_energy).pressure;
    EXPECT_NEAR(matrix_pressure / h.distention, h.pressure, 1e-9 * h.pressure) << up;
    EXPECT_NEAR(h.specific_energy, 0.5 * h.pressure * (1.0 / rho1 - 1.0 / h.bulk_density),
                1e-9 * h.specific_energy);
    EXPECT_NEAR(h.pressure, rho1 * h.shock_velocity * h.particle_velocity, 1e-9 * h.pressure);  // momentum
    EXPECT_NEAR(rho1 * h.shock_velocity, h.bulk_density * (h.shock_velocity - up),
                1e-9 * rho1 * h.shock_velocity);  // mass
    EXPECT_GT(h.pressure, last_pressure);         // the Hugoniot rises with u_p
    last_pressure = h.pressure;
    // A porous target has a lower shock impedance than the solid one at the same u_p.
    EXPECT_LT(h.pressure,
              test_support::hugoniot_at_particle_velocity(kBasaltMatrix, {2600.0, 0.0}, up).pressure);
  }
}

// Strong-shock limit of a porous material with Grueneisen parameter Gamma (Zel'dovich & Raizer 1967,
// ch. XI): V/V1 -> Gamma/(Gamma + 2). For Tillotson, Gamma = a + b/omega (= 2 for E << E0), so with
// alpha0 = 2 the fully compacted Hugoniot of basalt stays at the matrix density: rho -> rho1 (Gamma +
// 2)/Gamma = 2600 (Gamma = 2); at 20 GPa (E = 3.85 MJ/kg, omega = 1.0079, Gamma = 1.988) the limit is 2607.7
// kg/m^3.
TEST(PorousHugoniot, StrongShockLimitOfAPorousGrueneisenSolid) {
  const auto h = porous_hugoniot_at_pressure(kBasaltMatrix, kNominal, 20.0e9);
  const double eta = h.bulk_density / 2600.0;
  const double omega = h.specific_energy / (487.0e6 * eta * eta) + 1.0;
  const double gamma = 0.5 + 1.5 / omega;
  const double limit = 1300.0 * (gamma + 2.0) / gamma;
  EXPECT_NEAR(h.bulk_density / limit, 1.0, 2e-3);
  EXPECT_NEAR(h.shock_velocity / h.particle_velocity, 2.0, 5e-3);  // U_s = 2 u_p: snowplow-like
}

// Aluminium plate on the nominal porous target: equal pressure at the contact, and with alpha0 = 1 the
// solid impedance match.
TEST(PorousHugoniot, ImpedanceMatchWithAnAluminiumPlate) {
  for (double speed : {2000.0, 5000.0}) {
    const auto m =
        test_support::porous_impedance_match(kAluminium, {2700.0, 0.0}, kBasaltMatrix, kNominal, speed);
    EXPECT_NEAR(m.projectile.pressure, m.target.pressure, 1e-8 * m.pressure) << speed;
    EXPECT_NEAR(m.projectile.particle_velocity + m.particle_velocity, speed, 1e-9 * speed);
    EXPECT_EQ(m.target.distention, 1.0);  // GPa shocks compact the target fully
    // The porous target is softer: more of the impact speed goes into the target.
    const auto solid =
        test_support::impedance_match(kAluminium, {2700.0, 0.0}, kBasaltMatrix, {2600.0, 0.0}, speed);
    EXPECT_GT(m.particle_velocity, solid.particle_velocity);
    EXPECT_LT(m.pressure, solid.pressure);
  }
  sph::PAlphaParameters dense = kNominal;
  dense.initial_distention = 1.0;
  dense.transition_distention = 1.0;
  const auto porous =
      test_support::porous_impedance_match(kAluminium, {2700.0, 0.0}, kBasaltMatrix, dense, 3000.0);
  const auto solid =
      test_support::impedance_match(kAluminium, {2700.0, 0.0}, kBasaltMatrix, {2600.0, 0.0}, 3000.0);
  EXPECT_NEAR(porous.pressure, solid.pressure, 1e-7 * solid.pressure);
  EXPECT_NEAR(porous.particle_velocity, solid.particle_velocity, 1e-7 * solid.particle_velocity);
}

}  // namespace
