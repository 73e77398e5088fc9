// Strength kernels driven along prescribed strain paths by a small independent driver (explicit time
// stepping of dS/dt, not the solver's loop): Hooke + Jaumann elasticity, Lundborg yield with tension
// cut-off and pressure floor, radial return on sqrt(J2), and linear strain weakening of cohesion.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "craterkit/sph/physics/deviatoric_stress.hpp"
#include "craterkit/sph/physics/yield_strength.hpp"

namespace {
using namespace craterkit::sph;

constexpr double kShearModulus = 1.0e7;  // Pa

Tensor3 pure_shear(double shear_rate) {  // symmetric: no rotation, eps_xy = shear_rate / 2
  Tensor3 L{};
  L[0][1] = L[1][0] = 0.5 * shear_rate;
  return L;
}

TEST(Strength, FrictionFromReposeAngle) {
  // f = 2 sqrt(2) sin(theta) / (3 - sin(theta)): hand values 30 deg -> 2*1.41421356*0.5/2.5.
  EXPECT_NEAR(friction_from_repose_angle(30.0 * std::numbers::pi / 180.0), 0.565685424949238, 1e-14);
  EXPECT_NEAR(friction_from_repose_angle(22.0 * std::numbers::pi / 180.0), 0.40, 0.005);
  EXPECT_DOUBLE_EQ(friction_from_repose_angle(0.0), 0.0);
}

TEST(Strength, LundborgCurveHandValues) {
  const LundborgStrength law{100.0, 0.6, 3.5e9};
  // P = 1 MPa: 100 + 0.6e6 / (1 + 0.6e6 / (3.5e9 - 100)).
  EXPECT_NEAR(lundborg_yield_strength(law, 100.0, 1.0e6), 100.0 + 0.6e6 / (1.0 + 0.6e6 / (3.5e9 - 100.0)),
              1e-9);
  // Far above: tends to Y_dm.
  EXPECT_NEAR(lundborg_yield_strength(law, 100.0, 1.0e15), 3.5e9, 3.5e9 * 1e-5);
  // Tension: linear extension reaching zero at P = -Y0/f.
  EXPECT_DOUBLE_EQ(lundborg_yield_strength(law, 100.0, -50.0), 100.0 - 30.0);
  EXPECT_DOUBLE_EQ(lundborg_yield_strength(law, 100.0, -100.0 / 0.6), 0.0);
  EXPECT_DOUBLE_EQ(lundborg_yield_strength(law, 100.0, -1000.0), 0.0);
  // Continuous at P = 0 with value Y0.
  EXPECT_DOUBLE_EQ(lundborg_yield_strength(law, 100.0, 0.0), 100.0);
  EXPECT_NEAR(lundborg_yield_strength(law, 100.0, -1e-9), 100.0, 1e-9);
}

TEST(Strength, PressureFloorTakesTheFirstLimitReached) {
  // f < 1: floor -Y0 (tensile strength -Y0/f lies beyond it); f > 1: floor -Y0/f.
  EXPECT_DOUBLE_EQ(lundborg_pressure_floor({100.0, 0.5, 3.5e9}, 100.0), -100.0);
  EXPECT_DOUBLE_EQ(lundborg_pressure_floor({100.0, 2.0, 3.5e9}, 100.0), -50.0);
  // Cohesionless: no tension at all.
  EXPECT_DOUBLE_EQ(lundborg_pressure_floor({0.0, 0.6, 3.5e9}, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(lundborg_yield_strength({0.0, 0.6, 3.5e9}, 0.0, -1.0), 0.0);
}

TEST(Strength, ElasticPureShearIsHookean) {
  // Below yield, S_xy = 2 G eps_xy t exactly (no spin for a symmetric gradient).
  const double rate = 1e-3, dt = 1e-3;
  DeviatoricStress s;
  for (int n = 0; n < 100; ++n) {
    const auto ds = jaumann_stress_rate(s, pure_shear(rate), kShearModulus);
    s = {s.xx + dt * ds.xx, s.xy + dt * ds.xy, s.xz + dt * ds.xz, s.yy + dt * ds.yy, s.yz + dt * ds.yz};
  }
  EXPECT_NEAR(s.xy, kShearModulus * rate * 0.1, 1e-9 * kShearModulus * rate * 0.1);
  EXPECT_DOUBLE_EQ(s.xx, 0.0);
  EXPECT_NEAR(std::sqrt(second_invariant(s)), std::abs(s.xy), 1e-12);
}

TEST(Strength, JaumannRateRotatesStressRigidly) {
  // A pure rotation about z at rate w: S(t) = R S0 R^T. Integrate with RK4 and compare.
  const double w = 2.0;
  Tensor3 L{};
  L[0][1] = -w;  // v = (-w y, w x, 0): dv_x/dy = -w, dv_y/dx = w
  L[1][0] = w;
  const DeviatoricStress s0{3.0, 1.0, 0.5, -1.0, 0.25};
  auto add = [](const DeviatoricStress& a, const DeviatoricStress& b, double k) {
    return DeviatoricStress{a.xx + k * b.xx, a.xy + k * b.xy, a.xz + k * b.xz, a.yy + k * b.yy,
                            a.yz + k * b.yz};
  };
  DeviatoricStress s = s0;
  const double dt = 1e-3, t_end = 0.5;
  for (int n = 0; n < static_cast<int>(t_end / dt + 0.5); ++n) {
    const auto k1 = jaumann_stress_rate(s, L, 0.0);
    const auto k2 = jaumann_stress_rate(add(s, k1, dt / 2), L, 0.0);
    const auto k3 = jaumann_stress_rate(add(s, k2, dt / 2), L, 0.0);
    const auto k4 = jaumann_stress_rate(add(s, k3, dt), L, 0.0);
    s = add(s, add(add(k1, k4, 1.0), add(k2, k3, 1.0), 2.0), dt / 6.0);
  }
  const double c = std::cos(w * t_end), sn = std::sin(w * t_end);
  const Tensor3 R{{{c, -sn, 0.0}, {sn, c, 0.0}, {0.0, 0.0, 1.0}}};
  const Tensor3 S0 = s0.full();
  Tensor3 expected{};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) expected[a][b] += R[a][k] * S0[k][l] * R[b][l];
  const Tensor3 got = s.full();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) EXPECT_NEAR(got[a][b], expected[a][b], 1e-9) << a << b;
  EXPECT_NEAR(second_invariant(s), second_invariant(s0), 1e-9);
}

TEST(Strength, RadialReturnScalesOntoTheSurface) {
  const DeviatoricStress s{30.0, 40.0, 0.0, -30.0, 0.0};
  const double j2 = second_invariant(s);  // (900 + 900 + 0)/2 + 1600 = 2500
  EXPECT_DOUBLE_EQ(j2, 2500.0);
  const auto r = radial_return(s, 25.0);
  EXPECT_NEAR(std::sqrt(second_invariant(r)), 25.0, 1e-12);
  EXPECT_DOUBLE_EQ(r.xy / r.xx, s.xy / s.xx);  // direction kept
  const auto untouched = radial_return(s, 60.0);
  EXPECT_DOUBLE_EQ(untouched.xy, s.xy);
  EXPECT_DOUBLE_EQ(std::sqrt(second_invariant(radial_return(s, 0.0))), 0.0);
}

// The independent driver: pure shear at a prescribed pressure history, with strain weakening.
struct PathState {
  DeviatoricStress stress;
  double total_strain = 0.0;
};

PathState drive(const LundborgStrength& law, double shear_rate, double pressure, double t_end, double dt,
                double* max_excess = nullptr) {
  PathState st;
  const auto L = pure_shear(shear_rate);
  double worst = 0.0;
  for (int n = 0; n < static_cast<int>(t_end / dt + 0.5); ++n) {
    const auto ds = jaumann_stress_rate(st.stress, L, kShearModulus);
    st.stress = {st.stress.xx + dt * ds.xx, st.stress.xy + dt * ds.xy, st.stress.xz + dt * ds.xz,
                 st.stress.yy + dt * ds.yy, st.stress.yz + dt * ds.yz};
    st.total_strain += dt * deviatoric_strain_rate_invariant(L);
    const double cohesion = weakened_cohesion(law.cohesion, st.total_strain);
    const double p = std::max(pressure, lundborg_pressure_floor(law, cohesion));
    const double y = lundborg_yield_strength(law, cohesion, p);
    st.stress = radial_return(st.stress, y);
    worst = std::max(worst, std::sqrt(second_invariant(st.stress)) - y);
  }
  if (max_excess) *max_excess = worst;
  return st;
}

TEST(Strength, ShearPathFollowsLundborgWithWeakening) {
  const LundborgStrength law{1000.0, 0.55, 3.5e9};
  const double rate = 0.02, dt = 1e-3, pressure = 500.0;
  for (double t_end : {5.0, 20.0, 60.0, 120.0}) {
    double excess = 0.0;
    const auto st = drive(law, rate, pressure, t_end, dt, &excess);
    // Accumulated strain = (rate / 2) t for pure shear with eps_xy = rate / 2.
    EXPECT_NEAR(st.total_strain, 0.5 * rate * t_end, 1e-9);
    const double cohesion = law.cohesion * std::max(0.0, 1.0 - 0.5 * rate * t_end);
    const double expected = cohesion + 0.55 * pressure / (1.0 + 0.55 * pressure / (3.5e9 - cohesion));
    // Yielded (elastic stress G*rate*t far exceeds Y): on the surface to round-off.
    EXPECT_NEAR(std::sqrt(second_invariant(st.stress)), expected, 1e-9 * expected) << t_end;
    EXPECT_LE(excess, 1e-9 * law.cohesion);
  }
}

TEST(Strength, TensionCutOffAndFloorOnTheShearPath) {
  const LundborgStrength law{1000.0, 0.5, 3.5e9};
  // Applied tension -1500 Pa is below the floor -Y0 min(1, 1/f) = -1000 Pa: the floor applies and
  // Y = max(0, Y0 + f P_floor) = 500 Pa.
  const auto st = drive(law, 0.02, -1500.0, 1.0, 1e-3);
  const double cohesion = 1000.0 * (1.0 - 0.01);
  const double p_floor = -cohesion;
  EXPECT_NEAR(std::sqrt(second_invariant(st.stress)), cohesion + 0.5 * p_floor, 1e-9 * cohesion);
  // With f = 2 the floor is -Y0/2, where Y reaches zero: the material carries no shear.
  const auto st2 = drive({1000.0, 2.0, 3.5e9}, 0.02, -1500.0, 1.0, 1e-3);
  EXPECT_NEAR(std::sqrt(second_invariant(st2.stress)), 0.0, 1e-9);
}

TEST(Strength, CohesionFallsLinearlyAndIsLostAtUnitStrain) {
  EXPECT_DOUBLE_EQ(weakened_cohesion(10.0, 0.0), 10.0);
  EXPECT_DOUBLE_EQ(weakened_cohesion(10.0, 0.25), 7.5);
  EXPECT_DOUBLE_EQ(weakened_cohesion(10.0, 1.0), 0.0);
  EXPECT_DOUBLE_EQ(weakened_cohesion(10.0, 3.0), 0.0);
  // Past unit strain the cohesionless material at zero pressure holds no shear stress.
  const auto st = drive({1000.0, 0.55, 3.5e9}, 0.02, 0.0, 150.0, 1e-3);
  EXPECT_NEAR(std::sqrt(second_invariant(st.stress)), 0.0, 1e-12);
}

TEST(Strength, DeviatoricStrainRateInvariantIgnoresVolumeChange) {
  Tensor3 isotropic{};
  isotropic[0][0] = isotropic[1][1] = isotropic[2][2] = 0.3;
  EXPECT_NEAR(deviatoric_strain_rate_invariant(isotropic), 0.0, 1e-15);
  Tensor3 rotation{};
  rotation[0][1] = -1.0;
  rotation[1][0] = 1.0;
  EXPECT_NEAR(deviatoric_strain_rate_invariant(rotation), 0.0, 1e-15);
  // Uniaxial strain rate e along x: deviator diag(2e/3, -e/3, -e/3): sqrt((4/9+1/9+1/9) e^2 / 2) = e/sqrt(3).
  Tensor3 uniaxial{};
  uniaxial[0][0] = 0.6;
  EXPECT_NEAR(deviatoric_strain_rate_invariant(uniaxial), 0.6 / std::sqrt(3.0), 1e-14);
}

// The plastic strain rate of a stress on the yield surface equals what a radial return removes per unit
// time: (sqrt(J2_trial) - Y) / (2 G) / dt for the elastic trial step S + dt dS/dt from the surface.
TEST(Strength, PlasticStrainRateIsWhatTheRadialReturnRemoves) {
  // sqrt(J2) of the stress below is 650 Pa; the trial step differs from the rate by O(G dt / Y) relative.
  const double y = 500.0, dt = 1e-9;
  Tensor3 L{};  // a general gradient: shear, stretch and spin
  L[0][0] = 0.013;
  L[0][1] = 0.021;
  L[1][0] = -0.004;
  L[1][1] = -0.007;
  L[1][2] = 0.011;
  L[2][0] = 0.006;
  L[2][2] = 0.002;
  const DeviatoricStress on_surface = radial_return({300.0, 500.0, -200.0, -100.0, 250.0}, y);
  const auto rate = jaumann_stress_rate(on_surface, L, kShearModulus);
  const DeviatoricStress trial{on_surface.xx + dt * rate.xx, on_surface.xy + dt * rate.xy,
                               on_surface.xz + dt * rate.xz, on_surface.yy + dt * rate.yy,
                               on_surface.yz + dt * rate.yz};
  const double removed_per_time = (std::sqrt(second_invariant(trial)) - y) / (2.0 * kShearModulus) / dt;
  const double plastic = plastic_strain_rate_at_yield(on_surface, L);
  ASSERT_GT(removed_per_time, 0.0);
  EXPECT_NEAR(plastic, removed_per_time, 1e-5 * removed_per_time);
  // Never more than the total strain rate (Cauchy-Schwarz), equal to it for a flow along S.
  EXPECT_LE(plastic, deviatoric_strain_rate_invariant(L));
  Tensor3 along{};
  const Tensor3 S = on_surface.full();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) along[a][b] = 1e-4 * S[a][b];
  EXPECT_NEAR(plastic_strain_rate_at_yield(on_surface, along), deviatoric_strain_rate_invariant(along),
              1e-12 * deviatoric_strain_rate_invariant(along));
  // Unloading (the reverse gradient) and a stress-free state accumulate nothing.
  Tensor3 reverse{};
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) reverse[a][b] = -L[a][b];
  EXPECT_EQ(plastic_strain_rate_at_yield(on_surface, reverse), 0.0);
  EXPECT_EQ(plastic_strain_rate_at_yield({}, L), 0.0);
}

}  // namespace
