// Hugoniots and the impedance match (tests/support) against closed forms (ideal gas), the exact
// Riemann solver, and the weak-shock expansion of the Tillotson Hugoniot.
#include <gtest/gtest.h>

#include <cmath>

#include "craterkit/sph/physics/eos.hpp"
#include "support/exact_riemann.hpp"
#include "support/hugoniot.hpp"

namespace {

using craterkit::sph::IdealGas;
using craterkit::sph::Tillotson;
using craterkit::test_support::ExactRiemannSolver;
using craterkit::test_support::hugoniot_at_density;
using craterkit::test_support::hugoniot_at_particle_velocity;
using craterkit::test_support::impedance_match;
using craterkit::test_support::InitialState;

constexpr Tillotson basalt{2700.0, 26.7e9, 26.7e9, 487.0e6, 4.72e6, 18.2e6, 0.5, 1.5, 5.0, 5.0, 0.01};
constexpr Tillotson aluminium{2700.0, 75.2e9, 65.0e9, 5.0e6, 3.0e6, 13.9e6, 0.5, 1.63, 5.0, 5.0, 0.01};

TEST(Hugoniot, IdealGasClosedForm) {
  // rho/rho1 = ((g+1) P + (g-1) P1) / ((g-1) P + (g+1) P1) (e.g. Zel'dovich & Raizer; Toro eq. 3.55).
  const double g = 1.4, rho1 = 1.0, p1 = 1.0;
  const InitialState initial{rho1, p1 / ((g - 1.0) * rho1)};
  for (const double compression : {1.01, 1.5, 3.0, 5.5}) {
    const auto h = hugoniot_at_density(IdealGas{g}, initial, compression * rho1);
    const double p = h.pressure / p1;
    EXPECT_NEAR(compression, ((g + 1.0) * p + (g - 1.0)) / ((g - 1.0) * p + (g + 1.0)), 1e-11 * compression);
    EXPECT_NEAR(h.pressure - p1, rho1 * h.shock_velocity * h.particle_velocity, 1e-10 * h.pressure);
  }
  // No shocked state beyond the strong-shock limit (g+1)/(g-1) = 6.
  EXPECT_THROW(hugoniot_at_density(IdealGas{g}, initial, 6.5 * rho1), std::domain_error);
}

TEST(Hugoniot, ImpedanceMatchEqualsExactRiemannSolution) {
  // Two ideal-gas slabs at the same pressure collide: the Riemann problem with u_L = impact speed,
  // u_R = 0 has two shocks; its p* and u* are the impedance match.
  const double g = 5.0 / 3.0, p1 = 1.0;
  for (const auto& [rho_projectile, rho_target, speed] :
       {std::tuple{1.0, 1.0, 2.0}, std::tuple{1.0, 0.25, 3.0}, std::tuple{4.0, 1.0, 0.5}}) {
    const ExactRiemannSolver riemann(g, {rho_projectile, speed, p1}, {rho_target, 0.0, p1});
    const auto match = impedance_match(IdealGas{g}, {rho_projectile, p1 / ((g - 1.0) * rho_projectile)},
                                       IdealGas{g}, {rho_target, p1 / ((g - 1.0) * rho_target)}, speed);
    EXPECT_NEAR(match.pressure, riemann.star().pressure, 1e-10 * riemann.star().pressure);
    EXPECT_NEAR(match.particle_velocity, riemann.star().velocity, 1e-10 * speed);
    EXPECT_NEAR(match.target.density, riemann.star().density_right, 1e-9 * rho_target);
    EXPECT_NEAR(match.projectile.density, riemann.star().density_left, 1e-9 * rho_projectile);
  }
}

TEST(Hugoniot, TillotsonWeakShockExpansion) {
  // On the Hugoniot E = (P/2)(1/rho0 - 1/rho) = A chi^2/(2 rho0) + O(chi^3), so the thermal term adds
  // (a + b) rho0 E = (a + b) A chi^2 / 2 to the cold A chi + B chi^2:
  //   P_H = A chi + [B + (a + b) A/2] chi^2 + O(chi^3),  and  U_s -> sqrt(A/rho0) as u_p -> 0.
  for (const Tillotson& m : {basalt, aluminium}) {
    const double chi = 1e-4;
    const auto h = hugoniot_at_density(m, {m.reference_density}, m.reference_density * (1.0 + chi));
    const double quadratic = (h.pressure - m.A * chi) / (chi * chi);
    EXPECT_NEAR(quadratic, m.B + 0.5 * (m.a + m.b) * m.A, 1e-3 * (m.B + m.A));
    EXPECT_NEAR(h.specific_energy, m.A * chi * chi / (2.0 * m.reference_density), 1e-3 * h.specific_energy);
    const auto slow = hugoniot_at_particle_velocity(m, {m.reference_density}, 0.01);
    EXPECT_NEAR(slow.shock_velocity, std::sqrt(m.A / m.reference_density), 1e-5 * slow.shock_velocity);
  }
}

TEST(Hugoniot, TillotsonStatesSatisfyTheJumpConditions) {
  for (const Tillotson& m : {basalt, aluminium}) {
    for (const double up : {100.0, 1000.0, 3000.0}) {
      const auto h = hugoniot_at_particle_velocity(m, {m.reference_density}, up);
      const double rho0 = m.reference_density;
      EXPECT_NEAR(h.particle_velocity, up, 1e-9 * up);
      EXPECT_NEAR(evaluate(m, h.density, h.specific_energy).pressure, h.pressure, 1e-12 * h.pressure);
      EXPECT_NEAR(rho0 * h.shock_velocity, h.density * (h.shock_velocity - up),
                  1e-9 * rho0 * h.shock_velocity);
      EXPECT_NEAR(h.pressure, rho0 * h.shock_velocity * up, 1e-9 * h.pressure);
      EXPECT_NEAR(h.specific_energy, 0.5 * up * up, 1e-9 * h.specific_energy);  // E - E1 = u_p^2/2 for P1 = 0
    }
  }
}

TEST(ImpedanceMatch, SymmetricAndAcousticLimits) {
  // Identical plates: the contact moves at half the impact speed.
  const auto same = impedance_match(basalt, {2700.0}, basalt, {2700.0}, 4000.0);
  EXPECT_NEAR(same.particle_velocity, 2000.0, 1e-9 * 2000.0);
  // Slow impact: linear acoustics, u = v Z_p/(Z_p + Z_t), Z = rho0 sqrt(A/rho0).
  const double z_al = std::sqrt(aluminium.A * aluminium.reference_density);
  const double z_basalt = std::sqrt(basalt.A * basalt.reference_density);
  const double v = 0.1;
  const auto slow = impedance_match(aluminium, {2700.0}, basalt, {2700.0}, v);
  EXPECT_NEAR(slow.particle_velocity, v * z_al / (z_al + z_basalt), 1e-4 * v);
  EXPECT_NEAR(slow.pressure, z_basalt * slow.particle_velocity, 1e-4 * slow.pressure);
}

TEST(ImpedanceMatch, AluminiumOnBasaltIsConsistent) {
  for (const double v : {2000.0, 5000.0}) {
    const auto match = impedance_match(aluminium, {2700.0}, basalt, {2700.0}, v);
    // Equal pressure and velocity at the contact; aluminium, the stiffer plate, is slowed less than
    // the basalt is accelerated.
    EXPECT_NEAR(match.projectile.pressure, match.target.pressure, 1e-9 * match.pressure);
    EXPECT_NEAR(match.projectile.particle_velocity + match.target.particle_velocity, v, 1e-9 * v);
    EXPECT_GT(match.particle_velocity, 0.5 * v);
    EXPECT_LT(match.particle_velocity, v);
    // Shock heating stays below incipient vaporisation of basalt at these speeds (E = u_p^2/2).
    EXPECT_LT(match.target.specific_energy, basalt.E_iv);
  }
}

}  // namespace
