// Relative rates through the real inverse scaling law (craterkit::scaling) against the closed forms of
// the pure strength and pure gravity regimes for a single power law (derivation in relative_rates.hpp).
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gtest/gtest.h>

#include <cmath>

#include "craterkit/chronology/body.hpp"
#include "craterkit/chronology/relative_rates.hpp"
#include "craterkit/chronology/scaled_production.hpp"

namespace ck = craterkit::chronology;
namespace sc = craterkit::scaling;

namespace {

ck::ProductionSetup setup(double q) {
  ck::ProductionSetup s;
  s.population = ck::power_law_population(q);
  s.intrinsic_probability = ck::per_square_metre(2.86e-18);
  s.target_radius = 448.0;
  s.surface_area = 2.7e6;
  s.speeds = ck::single_speed(5300.0);
  s.cross_section = ck::CrossSection::target_only;
  return s;
}

sc::ScalingLaw ryugu_like() {
  sc::ScalingLaw law;
  law.form = sc::Form::hh2011;
  law.coefficient_1 = 0.60;
  law.coefficient_2 = 0.25;
  law.mu = 0.44;
  law.nu = 0.4;
  return law;
}

}  // namespace

TEST(ScaledRates, PureStrengthRegimeFollowsCohesionPower) {
  const double q = -4.0;
  const auto law = ryugu_like();
  const sc::Target weak{1190.0, 0.0, 0.05};
  const sc::Target strong{1190.0, 0.0, 1.0};
  const auto s = setup(q);
  for (double D : {22.0, 36.0, 120.0}) {
    const auto rr = ck::relative_rate(s, ck::scaled_impactor_radius(law, weak, 2600.0),
                                      ck::scaled_impactor_radius(law, strong, 2600.0), D);
    const double expected = std::pow(1.0 / 0.05, (q + 1.0) * law.mu / 2.0);
    EXPECT_NEAR(rr.ratio / expected, 1.0, 1e-9) << D;
  }
}

TEST(ScaledRates, PureGravityRegimeFollowsH1Power) {
  const double q = -3.5;
  auto law_a = ryugu_like();
  auto law_b = ryugu_like();
  law_b.coefficient_1 = 0.9;
  const sc::Target cohesionless{1190.0, 1.4e-4, 0.0};
  const auto s = setup(q);
  const auto rr = ck::relative_rate(s, ck::scaled_impactor_radius(law_a, cohesionless, 2600.0),
                                    ck::scaled_impactor_radius(law_b, cohesionless, 2600.0), 50.0);
  const double expected = std::pow(0.9 / 0.6, -(2.0 + law_a.mu) * (q + 1.0) / 2.0);
  EXPECT_NEAR(rr.ratio / expected, 1.0, 1e-9);
  // In pure gravity the cohesion does not matter: the same law gives ratio 1 between two "cohesions" of zero.
  const auto same = ck::relative_rate(s, ck::scaled_impactor_radius(law_a, cohesionless, 2600.0),
                                      ck::scaled_impactor_radius(law_a, cohesionless, 2600.0), 50.0);
  EXPECT_DOUBLE_EQ(same.ratio, 1.0);
}

TEST(ScaledRates, ImpactorRadiusReproducesTheCrater) {
  // The impactor the production uses makes, through the forward law, the crater it was solved for.
  const auto law = ryugu_like();
  const sc::Target target{1190.0, 1.4e-4, 0.05};
  const auto a_of_R = ck::scaled_impactor_radius(law, target, 2600.0);
  const double R = 36.0 / 2.0 / 1.2;
  const double a = a_of_R(R, 5300.0);
  EXPECT_NEAR(sc::crater_radius(law, sc::Impactor{a, 2600.0, 5300.0}, target) / R, 1.0, 1e-10);
}

TEST(ScaledRates, DifferentialProductionIntegratesToCumulative) {
  // The crater production through the real law and the shipped population: the integral of -dr/dD over
  // [D1, D2] (GSL QAG in ln D) equals r(D1) - r(D2), for a gravity-dominated and a strength-dominated law.
  gsl_set_error_handler_off();
  const auto body = ck::load_body("ryugu");
  auto s = ck::production_setup_for_body(body, ck::CollisionRegion::main_belt,
                                         ck::load_population("main_belt_approx_bottke2005"));
  for (double cohesion : {0.0, 10.0}) {
    const sc::Target target{body.bulk_density, body.surface_gravity, cohesion};
    const auto law = ck::scaled_impactor_radius(ryugu_like(), target, 2600.0);
    struct Ctx {
      const ck::ProductionSetup* s;
      const ck::ImpactorRadiusFunction* law;
    } ctx{&s, &law};
    gsl_function f;
    f.function = [](double ln_d, void* p) {
      const auto* c = static_cast<Ctx*>(p);
      const double d = std::exp(ln_d);
      return ck::differential_production_rate(*c->s, *c->law, d) * d;
    };
    f.params = &ctx;
    const double d1 = 10.0, d2 = 300.0;
    gsl_integration_workspace* w = gsl_integration_workspace_alloc(200);
    double result = 0.0, error = 0.0;
    gsl_integration_qags(&f, std::log(d1), std::log(d2), 0.0, 1e-8, 200, w, &result, &error);
    gsl_integration_workspace_free(w);
    const double expected = ck::crater_production_rate(s, law, d1) - ck::crater_production_rate(s, law, d2);
    // -dr/dD is a central difference with relative step 1e-4 (error ~1e-8 relative away from table knots).
    EXPECT_NEAR(result / expected, 1.0, 1e-5) << cohesion;
  }
}
