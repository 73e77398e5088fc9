// Forward law, limits, regimes, the form identity and the inverse (docs/physics.md section 6).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/point_source.hpp"

namespace cs = craterkit::scaling;

namespace {

// Jutzi et al. (2022) Ryugu constants in the Housen & Holsapple (2011) form.
cs::ScalingLaw ryugu() {
  return {cs::Form::hh2011, 0.60, 0.25, 0.44, 0.4};
}

// The SCI impact: 2 kg of 2700 kg/m^3 (a = 0.05613 m) at 2 km/s into rho = 1300 kg/m^3, g = 1.4e-4 m/s^2.
cs::Impactor sci_impactor() {
  return {std::cbrt(3.0 * 2.0 / (4.0 * std::numbers::pi * 2700.0)), 2700.0, 2000.0};
}
cs::Target ryugu_target(double strength) {
  return {1300.0, 1.4e-4, strength};
}

// Reference values below were computed independently by hand in Python (plain float arithmetic of the
// formulas as printed in docs/physics.md, not the log-space code under test), e.g. for the HH2011 form:
//   m = 4/3 pi a^3 delta; pi2 = g a/U^2; pi3 = Y/(rho U^2); pi4 = rho/delta
//   R = H1 pi4^((2+mu-6nu)/(3(2+mu))) (pi2 + (H1/H2)^((2+mu)/mu) pi4^nu pi3^((2+mu)/2))^(-mu/(2+mu))
//   (m/rho)^(1/3)
constexpr double kSciGravityOnly = 8.909027448107791;   // Y = 0
constexpr double kSciY005 = 7.414824956359536;          // Y = 0.05 Pa (transitional)
constexpr double kSciY5 = 2.917764504848155;            // Y = 5 Pa (strength dominated)
constexpr double kSciStrengthOnly = 8.039164557976797;  // g = 0, Y = 0.05 Pa

}  // namespace

TEST(PointSource, SciRadiiMatchHandCalculationInBothLimitsAndBetween) {
  const auto a = sci_impactor();
  EXPECT_NEAR(cs::crater_radius(ryugu(), a, ryugu_target(0.0)), kSciGravityOnly, 1e-12 * kSciGravityOnly);
  EXPECT_NEAR(cs::crater_radius(ryugu(), a, ryugu_target(0.05)), kSciY005, 1e-12 * kSciY005);
  EXPECT_NEAR(cs::crater_radius(ryugu(), a, ryugu_target(5.0)), kSciY5, 1e-12 * kSciY5);
  cs::Target no_gravity = ryugu_target(0.05);
  no_gravity.gravity = 0.0;
  EXPECT_NEAR(cs::crater_radius(ryugu(), a, no_gravity), kSciStrengthOnly, 1e-12 * kSciStrengthOnly);
  EXPECT_NEAR(cs::gravity_limit_radius(ryugu(), a, ryugu_target(0.05)), kSciGravityOnly,
              1e-12 * kSciGravityOnly);
  EXPECT_NEAR(cs::strength_limit_radius(ryugu(), a, ryugu_target(0.05)), kSciStrengthOnly,
              1e-12 * kSciStrengthOnly);
}

TEST(PointSource, HolsappleFormMatchesHandCalculation) {
  // Dry-soil-like constants (K1 = 1.1 * 0.132^(1/3), K2 = 0.26, mu = 0.41, nu = 0.33), 1 m impactor of
  // 3000 kg/m^3 at 10 km/s into 1700 kg/m^3, g = 9.81, Y = 2e5 Pa; Python hand values as above with
  //   R = K1 (pi2 pi4^((6nu-2-mu)/(3mu)) + (K2 pi3 pi4^((6nu-2)/(3mu)))^((2+mu)/2))^(-mu/(2+mu))
  //   (m/rho)^(1/3)
  const cs::ScalingLaw law{cs::Form::holsapple, 0.5600807706625438, 0.26, 0.41, 0.33};
  const cs::Impactor impactor{1.0, 3000.0, 1.0e4};
  EXPECT_NEAR(cs::crater_radius(law, impactor, {1700.0, 9.81, 2e5}), 16.110970506850748, 1e-11);
  EXPECT_NEAR(cs::crater_radius(law, impactor, {1700.0, 9.81, 0.0}), 16.423118487031484, 1e-11);
}

TEST(PointSource, PureLimitsFollowTheirOwnPowerLaws) {
  // Gravity regime: R ~ a^(2/(2+mu)) U^(2mu/(2+mu)) at fixed everything else; strength regime: R ~ a U^mu.
  const auto law = ryugu();
  const auto a = sci_impactor();
  const double mu = law.mu;
  cs::Impactor bigger = a;
  bigger.radius *= 10.0;
  cs::Impactor faster = a;
  faster.velocity *= 3.0;
  const auto t = ryugu_target(0.05);
  EXPECT_NEAR(cs::gravity_limit_radius(law, bigger, t) / cs::gravity_limit_radius(law, a, t),
              std::pow(10.0, 2.0 / (2.0 + mu)), 1e-12);
  EXPECT_NEAR(cs::gravity_limit_radius(law, faster, t) / cs::gravity_limit_radius(law, a, t),
              std::pow(3.0, 2.0 * mu / (2.0 + mu)), 1e-12);
  EXPECT_NEAR(cs::strength_limit_radius(law, bigger, t) / cs::strength_limit_radius(law, a, t), 10.0, 1e-11);
  EXPECT_NEAR(cs::strength_limit_radius(law, faster, t) / cs::strength_limit_radius(law, a, t),
              std::pow(3.0, mu), 1e-12);
  // The joined law never exceeds either limit, and tends to the smaller one far inside a regime.
  const double r = cs::crater_radius(law, a, t);
  EXPECT_LT(r, cs::gravity_limit_radius(law, a, t));
  EXPECT_LT(r, cs::strength_limit_radius(law, a, t));
  cs::Impactor tiny = a;
  tiny.radius = 1e-4;  // strength-dominated
  EXPECT_NEAR(cs::crater_radius(law, tiny, t) / cs::strength_limit_radius(law, tiny, t), 1.0, 1e-3);
  cs::Impactor huge = a;
  huge.radius = 1e3;  // gravity-dominated
  EXPECT_NEAR(cs::crater_radius(law, huge, t) / cs::gravity_limit_radius(law, huge, t), 1.0, 1e-3);
}

TEST(PointSource, PiGroupsAndRatio) {
  const auto a = sci_impactor();
  const auto t = ryugu_target(0.05);
  const auto pi = cs::pi_groups(a, t);
  EXPECT_DOUBLE_EQ(pi.pi2, 1.4e-4 * a.radius / 4e6);
  EXPECT_DOUBLE_EQ(pi.pi3, 0.05 / (1300.0 * 4e6));
  EXPECT_DOUBLE_EQ(pi.pi4, 1300.0 / 2700.0);
  EXPECT_NEAR(cs::impactor_mass(a), 2.0, 1e-12);
  const double r = cs::crater_radius(ryugu(), a, t);
  EXPECT_NEAR(cs::pi_R(ryugu(), pi), r * std::cbrt(1300.0 / 2.0), 1e-10);
  // R/a = pi_R (3 rho / (4 pi delta))^(-1/3)
  EXPECT_NEAR(cs::radius_ratio(ryugu(), a, t),
              cs::pi_R(ryugu(), pi) * std::pow(3.0 * 1300.0 / (4.0 * std::numbers::pi * 2700.0), -1.0 / 3.0),
              1e-9);
}

TEST(PointSource, FormsAgreeThroughTheConversionIdentity) {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> h(0.1, 2.0), mu(1.0 / 3.0, 2.0 / 3.0), nu(0.2, 0.6),
      log10(-8.0, 4.0);
  for (int trial = 0; trial < 200; ++trial) {
    const cs::ScalingLaw hh{cs::Form::hh2011, h(random), h(random), mu(random), nu(random)};
    const cs::ScalingLaw holsapple = cs::convert(hh, cs::Form::holsapple);
    // K1 = H1 and K2 = (H1/H2)^(2/mu), written out independently here.
    EXPECT_DOUBLE_EQ(holsapple.coefficient_1, hh.coefficient_1);
    EXPECT_NEAR(holsapple.coefficient_2, std::pow(hh.coefficient_1 / hh.coefficient_2, 2.0 / hh.mu),
                1e-12 * holsapple.coefficient_2);
    const cs::ScalingLaw back = cs::convert(holsapple, cs::Form::hh2011);
    EXPECT_NEAR(back.coefficient_2, hh.coefficient_2, 1e-12 * hh.coefficient_2);
    const cs::Impactor impactor{std::pow(10.0, log10(random) / 3.0), 1000.0 + 7000.0 * h(random) / 2.0,
                                std::pow(10.0, 2.0 + log10(random) / 6.0)};
    const cs::Target target{800.0 + 2000.0 * h(random) / 2.0, std::pow(10.0, log10(random) / 2.0),
                            std::pow(10.0, 1.0 + log10(random) / 2.0)};
    const double r_hh = cs::crater_radius(hh, impactor, target);
    const double r_holsapple = cs::crater_radius(holsapple, impactor, target);
    EXPECT_NEAR(r_holsapple / r_hh, 1.0, 1e-11);
    const auto regime_hh = cs::regime(hh, impactor, target);
    const auto regime_holsapple = cs::regime(holsapple, impactor, target);
    EXPECT_NEAR(regime_hh.gravity_share, regime_holsapple.gravity_share, 1e-12);
  }
}

TEST(PointSource, RegimeSharesAndKinds) {
  const auto law = ryugu();
  const auto a = sci_impactor();
  const auto mid = cs::regime(law, a, ryugu_target(0.05));
  EXPECT_NEAR(mid.gravity_share + mid.strength_share, 1.0, 1e-15);
  EXPECT_EQ(mid.kind, cs::RegimeKind::transitional);
  // Hand check of the share: gravity term pi2 vs strength term (H1/H2)^((2+mu)/mu) pi4^nu pi3^((2+mu)/2).
  const auto pi = cs::pi_groups(a, ryugu_target(0.05));
  const double g = pi.pi2;
  const double s = std::pow(0.6 / 0.25, 2.44 / 0.44) * std::pow(pi.pi4, 0.4) * std::pow(pi.pi3, 2.44 / 2.0);
  EXPECT_NEAR(mid.gravity_share, g / (g + s), 1e-12);
  EXPECT_EQ(cs::regime(law, a, ryugu_target(50.0)).kind, cs::RegimeKind::strength);
  EXPECT_EQ(cs::regime(law, a, ryugu_target(0.0)).kind, cs::RegimeKind::gravity);
  EXPECT_EQ(cs::regime(law, a, ryugu_target(0.0)).gravity_share, 1.0);
  EXPECT_EQ(cs::to_string(cs::RegimeKind::transitional), "transitional");
}

TEST(PointSource, InverseRoundTripsToImpactorRadiusAndVelocity) {
  for (const auto& law : {ryugu(), cs::convert(ryugu(), cs::Form::holsapple)}) {
    for (double strength : {0.0, 0.05, 5.0, 5e4}) {
      for (double radius : {1e-4, 0.0561, 3.0, 500.0}) {
        cs::Impactor impactor = sci_impactor();
        impactor.radius = radius;
        const auto target = ryugu_target(strength);
        const double crater = cs::crater_radius(law, impactor, target);
        const double solved = cs::solve_impactor_radius(law, crater, impactor, target);
        EXPECT_NEAR(solved / radius, 1.0, 1e-9) << "strength " << strength << " radius " << radius;
        for (double velocity : {10.0, 2000.0, 2e4}) {
          cs::Impactor moving = impactor;
          moving.velocity = velocity;
          const double r = cs::crater_radius(law, moving, target);
          EXPECT_NEAR(cs::solve_velocity(law, r, moving, target) / velocity, 1.0, 1e-9);
        }
      }
    }
  }
  // The SCI crater: the impactor radius that makes the observed 7.25 m at 0.05 Pa.
  const double a = cs::solve_impactor_radius(ryugu(), 7.25, sci_impactor(), ryugu_target(0.05));
  cs::Impactor check = sci_impactor();
  check.radius = a;
  EXPECT_NEAR(cs::crater_radius(ryugu(), check, ryugu_target(0.05)), 7.25, 7.25e-9);
}

TEST(PointSource, InverseRoundTripsToStrength) {
  for (const auto& law : {ryugu(), cs::convert(ryugu(), cs::Form::holsapple)}) {
    for (double strength : {1e-3, 0.05, 5.0, 5e4}) {
      const double crater = cs::crater_radius(law, sci_impactor(), ryugu_target(strength));
      EXPECT_NEAR(cs::solve_strength(law, crater, sci_impactor(), ryugu_target(0.0)) / strength, 1.0, 1e-9)
          << "strength " << strength;
    }
  }
  // The cohesionless radius and anything larger cannot be made by a strength: named in the error.
  const double gravity_radius = cs::crater_radius(ryugu(), sci_impactor(), ryugu_target(0.0));
  try {
    cs::solve_strength(ryugu(), gravity_radius, sci_impactor(), ryugu_target(0.0));
    FAIL() << "no error";
  } catch (const craterkit::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("gravity-regime"), std::string::npos) << e.what();
  }
  EXPECT_THROW(cs::solve_strength(ryugu(), -1.0, sci_impactor(), ryugu_target(0.0)), craterkit::InputError);
}

TEST(PointSource, InverseReportsImpossibleProblems) {
  EXPECT_THROW(cs::solve_impactor_radius(ryugu(), 0.0, sci_impactor(), ryugu_target(0.05)),
               craterkit::InputError);
  EXPECT_THROW(cs::solve_impactor_radius(ryugu(), -1.0, sci_impactor(), ryugu_target(0.05)),
               craterkit::InputError);
  EXPECT_THROW(cs::solve_impactor_radius(ryugu(), std::numeric_limits<double>::quiet_NaN(), sci_impactor(),
                                         ryugu_target(0.05)),
               craterkit::InputError);
  cs::Target nothing{1300.0, 0.0, 0.0};  // no gravity, no strength: no finite crater
  EXPECT_THROW(cs::solve_impactor_radius(ryugu(), 1.0, sci_impactor(), nothing), craterkit::InputError);
  // A crater far beyond any impactor up to 1e30 m cannot be made: reported, not looped on.
  EXPECT_THROW(cs::solve_impactor_radius(ryugu(), 1e300, sci_impactor(), ryugu_target(0.05)),
               craterkit::InputError);
}

TEST(PointSource, BadInputsAreNamed) {
  cs::Impactor bad = sci_impactor();
  bad.velocity = -1.0;
  try {
    cs::crater_radius(ryugu(), bad, ryugu_target(0.05));
    FAIL() << "no error";
  } catch (const craterkit::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("impact velocity"), std::string::npos) << e.what();
  }
  cs::ScalingLaw law = ryugu();
  law.coefficient_2 = 0.0;
  try {
    cs::validate(law);
    FAIL() << "no error";
  } catch (const craterkit::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("H2"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(cs::validate(ryugu()));
}

TEST(PointSource, MissingConstantIsOnlyAnErrorWhenNeeded) {
  // A gravity-regime set that does not give H2 works for Y = 0 and names H2 otherwise.
  const cs::ScalingLaw sand{cs::Form::hh2011, 0.59, std::numeric_limits<double>::quiet_NaN(), 0.41, 0.4};
  const auto a = sci_impactor();
  const double r = cs::crater_radius(sand, a, ryugu_target(0.0));
  const auto pi = cs::pi_groups(a, ryugu_target(0.0));
  const double hand = 0.59 * std::pow(pi.pi2, -0.41 / 2.41) * std::pow(pi.pi4, (2.41 - 2.4) / (3.0 * 2.41)) *
                      std::cbrt(2.0 / 1300.0);
  EXPECT_NEAR(r, hand, 1e-12 * hand);
  try {
    cs::crater_radius(sand, a, ryugu_target(1.0));
    FAIL() << "no error";
  } catch (const craterkit::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("H2"), std::string::npos) << e.what();
  }
}
