// Tillotson (and ideal-gas) equation of state against independently computed values, and the
// continuity of the Tillotson branches (docs/physics.md section 2; tillotson.hpp states the choices).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <string_view>

#include "craterkit/sph/physics/eos.hpp"

namespace {

using craterkit::sph::EquationOfState;
using craterkit::sph::evaluate;
using craterkit::sph::IdealGas;
using craterkit::sph::Tillotson;

// docs/physics.md table: basalt (Benz & Asphaug 1999), aluminium (Tillotson 1962); c floor 0.01 sqrt(A/rho0).
constexpr Tillotson basalt{2700.0, 26.7e9, 26.7e9, 487.0e6, 4.72e6, 18.2e6, 0.5, 1.5, 5.0, 5.0, 0.01};
constexpr Tillotson aluminium{2700.0, 75.2e9, 65.0e9, 5.0e6, 3.0e6, 13.9e6, 0.5, 1.63, 5.0, 5.0, 0.01};

const Tillotson& material(std::string_view name) {
  return name == "basalt" ? basalt : aluminium;
}

struct Reference {
  const char* material;
  const char* branch;
  double density, energy;  // kg/m^3, J/kg
  double pressure, sound_speed, dp_ddensity, dp_denergy;
};

// Produced by tests/support/tillotson_reference_values.py: an independent implementation of the
// docs/physics.md pressure formulas in 50-digit arithmetic (mpmath), with the derivatives taken by
// high-precision numerical differentiation (not the analytic derivatives of tillotson.hpp) and
// c^2 = dP/drho + (P/rho^2) dP/dE floored at 0.01 sqrt(A/rho0). Hand check of the first rows:
//  - rho = rho0, E = 0: P = 0, c = sqrt(A/rho0) = sqrt(26.7e9/2700) = 3144.66 m/s (basalt),
//    sqrt(75.2e9/2700) = 5277.49 m/s (aluminium); dP/dE = rho0 (a + b) = 2700 * 2.0 = 5400 (basalt).
//  - basalt, rho = 3240 (eta = 1.2, chi = 0.2), E = 1e6: omega = 1e6/(487e6 * 1.44) + 1 = 1.0014259;
//    P = (0.5 + 1.5/omega) 3240 * 1e6 + 26.7e9 * 0.2 + 26.7e9 * 0.04 = 6.4730e9 + 5.34e9 + 1.068e9
//    = 12.881e9 Pa.
//  - basalt, rho = 2160 (eta = 0.8), E = 1e6 <= E_iv (cold expanded, no B chi^2 term): omega = 1.0032084,
//    P = (0.5 + 1.5/omega) 2160e6 - 0.2 * 26.7e9 = 4.3096e9 - 5.34e9 = -1.0304e9 Pa.
//  - last row of each material: mixed branch in deep tension, c^2 < 0, so c = the floor 0.01 sqrt(A/rho0).
constexpr std::array<Reference, 24> references{{
    // basalt
    {"basalt", "compressed", 2700.0, 0.0, 0.0, 3144.6603773522013, 9888888.8888888889, 5400.0},
    {"basalt", "compressed", 3240.0, 1000000.0, 12881079683.317194, 4876.5650779845342, 15846574.261895572,
     6466.1692207049647},
    {"basalt", "compressed", 4050.0, 20000000.0, 179847092762.71566, 12113.754343725315, 60296253.964256701,
     7884.1612433226837},
    {"basalt", "compressed", 5400.0, 100000000.0, 1093849218750.0, 24747.865333543898, 236275629.67936198,
     10028.296279907227},
    {"basalt", "cold", 2160.0, 1000000.0, -1030362031.4698719, 3308.1998057893149, 11893655.441039384,
     4299.3090764726556},
    {"basalt", "cold", 1350.0, 2000000.0, -8015454545.4545455, 1531.8634070611249, 13935806.550352005,
     2635.0743801652893},
    {"basalt", "mixed", 2160.0, 8000000.0, 27948014957.493807, 7167.4235035684664, 28796599.335588126,
     3768.697039155542},
    {"basalt", "mixed", 2565.0, 12000000.0, 58838522262.965503, 8970.9984009125645, 36843500.614358613,
     4879.2274609186309},
    {"basalt", "hot", 2160.0, 30000000.0, 96149886259.004753, 14292.525154623874, 141370530.83670665,
     3052.4533389109634},
    {"basalt", "hot", 810.0, 30000000.0, 12150000000.032566, 4743.4164905932536, 15000000.003199981,
     405.00000000064444},
    {"basalt", "hot", 1620.0, 100000000.0, 97727478807.85469, 14716.124105532709, 182425185.07437795,
     916.78120737695871},
    {"basalt", "mixed", 540.0, 5000000.0, -16410468668.179437, 31.446603773522013, 20414976.064900854,
     2117.7448969638475},
    // aluminium
    {"aluminium", "compressed", 2700.0, 0.0, 0.0, 5277.4853720168521, 27851851.851851852, 5751.0},
    {"aluminium", "compressed", 3240.0, 1000000.0, 23897151219.51219, 7260.7481928160257, 39761778.92348029,
     5691.6449732302198},
    {"aluminium", "compressed", 4050.0, 20000000.0, 141880800000.0, 10658.360877830797, 88684005.925925926,
     2880.5544},
    {"aluminium", "compressed", 5400.0, 100000000.0, 556900000000.0, 15958.657202657564, 198444444.44444444,
     2944.5},
    {"aluminium", "cold", 2160.0, 1000000.0, -11277485714.285711, 4757.5599624557846, 30185139.833711262,
     3123.8204081632656},
    {"aluminium", "cold", 1350.0, 2000000.0, -34557307692.307692, 3560.5603818039499, 31648893.271970195,
     1000.5177514792899},
    {"aluminium", "mixed", 2160.0, 8000000.0, 6109749283.2934373, 5498.3466641077557, 27318803.439892208,
     2224.4696060088209},
    {"aluminium", "mixed", 2565.0, 12000000.0, 25936174525.854303, 6697.8272284433144, 38327393.661172219,
     1657.3508038883222},
    {"aluminium", "hot", 2160.0, 30000000.0, 36695750201.523164, 6024.4290504490715, 27611142.828967372,
     1103.9302986804038},
    {"aluminium", "hot", 810.0, 30000000.0, 12150000000.00088, 4743.4164902618761, 15000000.000087744,
     405.00000000000042},
    {"aluminium", "hot", 1620.0, 100000000.0, 81389687467.799477, 8844.8423380123263, 53108187.524349139,
     810.0894650119912},
    {"aluminium", "mixed", 540.0, 5000000.0, -47633257233.592095, 52.774853720168521, 25989569.171255833,
     5774.7999267140763},
}};

// |actual - expected| <= rel |expected| + abs
void expect_close(double actual, double expected, double rel, double abs, const char* what,
                  const Reference& r) {
  EXPECT_LE(std::abs(actual - expected), rel * std::abs(expected) + abs)
      << what << " of " << r.material << " (" << r.branch << ") at rho = " << r.density
      << ", E = " << r.energy << ": got " << actual << ", expected " << expected;
}

TEST(Tillotson, MatchesIndependentValuesInEveryBranch) {
  int branches_seen = 0;
  for (const auto& r : references) {
    const Tillotson& m = material(r.material);
    const auto s = evaluate(m, r.density, r.energy);
    expect_close(s.pressure, r.pressure, 1e-12, 1e-12 * m.A, "pressure", r);
    expect_close(s.sound_speed, r.sound_speed, 1e-10, 0.0, "sound speed", r);
    expect_close(s.dpressure_ddensity, r.dp_ddensity, 1e-10, 0.0, "dP/drho", r);
    expect_close(s.dpressure_denergy, r.dp_denergy, 1e-10, 0.0, "dP/dE", r);
    ++branches_seen;
  }
  EXPECT_EQ(branches_seen, 24);
}

TEST(Tillotson, ColdExpandedBranchHasNoQuadraticTerm) {
  // At E = 0 and rho < rho0 only A chi survives (tillotson.hpp: B chi^2 dropped in expansion).
  for (const double eta : {0.99, 0.9, 0.5, 0.1}) {
    EXPECT_DOUBLE_EQ(evaluate(basalt, eta * 2700.0, 0.0).pressure, 26.7e9 * (eta - 1.0));
    EXPECT_DOUBLE_EQ(evaluate(aluminium, eta * 2700.0, 0.0).pressure, 75.2e9 * (eta - 1.0));
  }
  // ... and in compression both: A chi + B chi^2.
  EXPECT_NEAR(evaluate(aluminium, 2970.0, 0.0).pressure, 75.2e9 * 0.1 + 65.0e9 * 0.01, 1e-13 * 8.17e9);
}

// E < 0 is read as the cold state E = 0 (tillotson.hpp): no pole at E = -E0 eta^2, where the thermal factor
// b/omega would send P to -inf or +inf; P continuous at E = 0 from below.
TEST(Tillotson, NegativeEnergyIsTheColdStateWithoutThePole) {
  for (const Tillotson* m : {&basalt, &aluminium}) {
    const double rho0 = m->reference_density;
    for (const double eta : {0.8, 0.95, 1.0, 1.05, 1.3}) {
      const double rho = eta * rho0;
      const auto cold = evaluate(*m, rho, 0.0);
      const double pole = -m->E0 * eta * eta;
      for (const double e : {std::nextafter(0.0, -1.0), -1e3, 0.5 * pole, pole, std::nextafter(pole, 0.0),
                             std::nextafter(pole, -1e300), 3.0 * pole}) {
        const auto s = evaluate(*m, rho, e);
        EXPECT_EQ(s.pressure, cold.pressure) << "eta " << eta << " E " << e;
        EXPECT_EQ(s.dpressure_ddensity, cold.dpressure_ddensity) << "eta " << eta << " E " << e;
        EXPECT_EQ(s.dpressure_denergy, 0.0);
      }
      // The cold curve itself: A chi (+ B chi^2 in compression).
      const double chi = eta - 1.0;
      EXPECT_NEAR(cold.pressure, m->A * chi + (eta >= 1.0 ? m->B * chi * chi : 0.0), 1e-12 * m->A);
    }
  }
}

// Relative jump of f across a boundary, evaluated at the boundary value and its floating-point neighbour.
double relative_jump(double below, double above, double scale) {
  return std::abs(above - below) / scale;
}

TEST(Tillotson, PressureContinuousAcrossEveryBranchBoundary) {
  for (const Tillotson* m : {&basalt, &aluminium}) {
    const double rho0 = m->reference_density;
    const double just_below_rho0 = std::nextafter(rho0, 0.0);
    // rho = rho0: compressed against each expanded branch (cold, mixed, hot energies).
    for (const double e : {0.0, 1e5, m->E_iv, 0.5 * (m->E_iv + m->E_cv), m->E_cv, 3.0 * m->E_cv}) {
      const auto above = evaluate(*m, rho0, e);
      const auto below = evaluate(*m, just_below_rho0, e);
      EXPECT_LT(relative_jump(below.pressure, above.pressure, m->A), 1e-12) << "rho0, E = " << e;
      // dP/drho and c are continuous there as well (the B chi^2 term has zero slope at chi = 0).
      EXPECT_LT(relative_jump(below.sound_speed, above.sound_speed, above.sound_speed), 1e-9) << "E = " << e;
      EXPECT_LT(relative_jump(below.dpressure_ddensity, above.dpressure_ddensity, above.dpressure_ddensity),
                1e-9);
    }
    // E = E_iv and E = E_cv in expansion: cold -> mixed -> hot.
    for (const double eta : {0.95, 0.8, 0.5, 0.2}) {
      const double rho = eta * rho0;
      for (const double boundary : {m->E_iv, m->E_cv}) {
        const auto at = evaluate(*m, rho, boundary);
        const auto below = evaluate(*m, rho, std::nextafter(boundary, 0.0));
        const auto above = evaluate(*m, rho, std::nextafter(boundary, 1e300));
        EXPECT_LT(relative_jump(below.pressure, at.pressure, m->A), 1e-12)
            << "eta " << eta << " E " << boundary;
        EXPECT_LT(relative_jump(at.pressure, above.pressure, m->A), 1e-12)
            << "eta " << eta << " E " << boundary;
      }
    }
  }
}

TEST(Tillotson, AnalyticDerivativesMatchFiniteDifferencesInsideEachBranch) {
  for (const Tillotson* m : {&basalt, &aluminium}) {
    const double rho0 = m->reference_density;
    const std::array<std::array<double, 2>, 6> points{{{1.3 * rho0, 2e6},
                                                       {1.05 * rho0, 5e7},
                                                       {0.7 * rho0, 0.5 * m->E_iv},
                                                       {0.7 * rho0, 0.5 * (m->E_iv + m->E_cv)},
                                                       {0.7 * rho0, 2.0 * m->E_cv},
                                                       {0.4 * rho0, 1.5 * m->E_cv}}};
    for (const auto& [rho, e] : points) {
      const auto s = evaluate(*m, rho, e);
      const double hr = 1e-6 * rho;
      const double he = 1e-6 * e;
      const double fd_rho =
          (evaluate(*m, rho + hr, e).pressure - evaluate(*m, rho - hr, e).pressure) / (2 * hr);
      const double fd_e =
          (evaluate(*m, rho, e + he).pressure - evaluate(*m, rho, e - he).pressure) / (2 * he);
      EXPECT_NEAR(s.dpressure_ddensity, fd_rho, 1e-6 * std::abs(fd_rho) + 1e-7 * m->A / rho0)
          << "rho " << rho << " E " << e;
      EXPECT_NEAR(s.dpressure_denergy, fd_e, 1e-6 * std::abs(fd_e) + 1e-9 * rho)
          << "rho " << rho << " E " << e;
    }
  }
}

TEST(Tillotson, SoundSpeedNeverBelowTheFloorAndFiniteEverywhere) {
  for (const Tillotson* m : {&basalt, &aluminium}) {
    const double c_min = 0.01 * std::sqrt(m->A / m->reference_density);
    int floored = 0;
    for (double eta = 0.02; eta <= 3.0; eta += 0.02) {
      for (double e = 0.0; e <= 5e8; e += 2.5e5) {
        const auto s = evaluate(*m, eta * m->reference_density, e);
        ASSERT_TRUE(std::isfinite(s.pressure) && std::isfinite(s.sound_speed)) << eta << " " << e;
        ASSERT_GE(s.sound_speed, c_min * (1.0 - 1e-15));
        if (std::abs(s.sound_speed - c_min) <= 1e-15 * c_min) ++floored;
      }
    }
    EXPECT_GT(floored, 0);  // the floor is reached (mixed branch in deep tension), not just defined
  }
  // Extreme expansion: only the gas term a rho E is left, finite derivatives (no 0 * inf).
  for (const double rho : {1e-100, 1e-200, 1e-300}) {
    const auto s = evaluate(basalt, rho, 3.0 * basalt.E_cv);
    EXPECT_DOUBLE_EQ(s.pressure, 0.5 * rho * 3.0 * basalt.E_cv);
    EXPECT_TRUE(std::isfinite(s.dpressure_ddensity) && std::isfinite(s.dpressure_denergy)) << rho;
  }
  // Non-positive density: no pressure, the floor sound speed, no NaN.
  const auto empty = evaluate(basalt, 0.0, 1e6);
  EXPECT_EQ(empty.pressure, 0.0);
  EXPECT_DOUBLE_EQ(empty.sound_speed, 0.01 * std::sqrt(26.7e9 / 2700.0));
}

TEST(IdealGas, PressureAndSoundSpeedByHand) {
  const IdealGas gas{1.4};
  // P = 0.4 * 2 * 3 = 2.4; c = sqrt(1.4 * 0.4 * 3) = sqrt(1.68); dP/drho = 0.4 * 3; dP/dE = 0.4 * 2.
  const auto s = evaluate(gas, 2.0, 3.0);
  EXPECT_DOUBLE_EQ(s.pressure, 2.4);
  EXPECT_DOUBLE_EQ(s.sound_speed, std::sqrt(1.68));
  EXPECT_DOUBLE_EQ(s.dpressure_ddensity, 1.2);
  EXPECT_DOUBLE_EQ(s.dpressure_denergy, 0.8);
  EXPECT_EQ(evaluate(gas, 1.0, -1.0).sound_speed, 0.0);  // no NaN from a slightly negative energy
}

TEST(EquationOfState, VariantDispatchEqualsDirectCall) {
  const EquationOfState gas = IdealGas{5.0 / 3.0};
  const EquationOfState rock = basalt;
  EXPECT_EQ(evaluate(gas, 1.5, 2.0).pressure, evaluate(IdealGas{5.0 / 3.0}, 1.5, 2.0).pressure);
  const auto a = evaluate(rock, 3000.0, 1e6);
  const auto b = evaluate(basalt, 3000.0, 1e6);
  EXPECT_EQ(a.pressure, b.pressure);
  EXPECT_EQ(a.sound_speed, b.sound_speed);
}

}  // namespace
