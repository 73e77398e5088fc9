// A chronology-only downstream program: loads a shipped body and population through the data lookup
// (CRATERKIT_DATA_DIR is set by the install test) and evaluates a production rate.
#include <cmath>
#include <craterkit/chronology/body.hpp>
#include <craterkit/chronology/population.hpp>
#include <craterkit/chronology/production.hpp>
#include <craterkit/chronology/scaled_production.hpp>
#include <cstdio>

int main() {
  using namespace craterkit;
  const auto body = chronology::load_body("ryugu");
  const auto setup = chronology::production_setup_for_body(body, chronology::CollisionRegion::main_belt,
                                                           chronology::power_law_population(-3.0));
  const scaling::ScalingLaw law{scaling::Form::hh2011, 0.6, 0.25, 0.44, 0.4};
  const auto radius = chronology::scaled_impactor_radius(law, {1300.0, body.surface_gravity, 0.05}, 2700.0);
  const double rate = chronology::crater_production_rate(setup, radius, 20.0);
  std::printf("%s: g = %.3g m/s^2, r(>20 m) = %.3g per m^2 per year\n", body.name.c_str(),
              body.surface_gravity, rate);
  return (std::isfinite(rate) && rate > 0.0) ? 0 : 1;
}
