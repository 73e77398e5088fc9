// Impactor populations: closed forms of power laws, consistency of differential and cumulative numbers
// (numerical integration with GSL), table interpolation and file errors.
#include <gsl/gsl_errno.h>
#include <gsl/gsl_integration.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "craterkit/chronology/population.hpp"
#include "craterkit/common/input_error.hpp"

namespace ck = craterkit::chronology;

namespace {

// Integral of dN/da from a to a_max (finite) with GSL QAG in ln a (smooth for power laws).
double integrate_differential(const ck::ImpactorPopulation& p, double a, double a_max) {
  gsl_set_error_handler_off();  // a kinked (table) integrand may not reach 1e-11; the assertions judge
  gsl_integration_workspace* w = gsl_integration_workspace_alloc(1000);
  struct Ctx {
    const ck::ImpactorPopulation* p;
  } ctx{&p};
  gsl_function f;
  f.function = [](double ln_a, void* data) {
    const auto* c = static_cast<Ctx*>(data);
    const double x = std::exp(ln_a);
    return ck::differential_number(*c->p, x) * x;
  };
  f.params = &ctx;
  double result = 0.0, error = 0.0;
  gsl_integration_qags(&f, std::log(a), std::log(a_max), 0.0, 1e-11, 1000, w, &result, &error);
  gsl_integration_workspace_free(w);
  return result;
}

std::filesystem::path temp_file(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / ("ck_chron_" + name);
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST(Population, PowerLawClosedForm) {
  const auto p = ck::power_law_population(-4.0, 2.0, 100.0);
  EXPECT_DOUBLE_EQ(ck::cumulative_number(p, 2.0), 100.0);
  // N(>a) = 100 (a/2)^-3
  EXPECT_NEAR(ck::cumulative_number(p, 20.0), 0.1, 1e-15);
  // dN/da = 3 * 100 * (a/2)^-3 / a
  EXPECT_NEAR(ck::differential_number(p, 4.0), 3.0 * 100.0 / 8.0 / 4.0, 1e-14);
}

TEST(Population, DifferentialIntegratesToCumulativePowerLaw) {
  const auto p = ck::power_law_population(-3.5, 1.0, 1e6);
  const double a = 0.3, b = 40.0;
  const double expected = ck::cumulative_number(p, a) - ck::cumulative_number(p, b);
  EXPECT_NEAR(integrate_differential(p, a, b), expected, 1e-9 * expected);
}

TEST(Population, BrokenPowerLawIsContinuousAndConsistent) {
  ck::ImpactorPopulation p;
  p.name = "test";
  p.shape = ck::BrokenPowerLaw{{1.0, 50.0}, {-3.2, -2.1, -4.0}, 10.0, 1e5};
  ck::validate(p);
  EXPECT_NEAR(ck::cumulative_number(p, 10.0), 1e5, 1e-9 * 1e5);
  // dN/da continuous across the breaks.
  for (double brk : {1.0, 50.0}) {
    const double below = ck::differential_number(p, brk * (1 - 1e-12));
    const double above = ck::differential_number(p, brk * (1 + 1e-12));
    EXPECT_NEAR(below / above, 1.0, 1e-9);
  }
  // Differential integrates to the cumulative difference across both breaks.
  for (auto [a, b] : {std::pair{0.2, 0.9}, std::pair{0.5, 70.0}, std::pair{3.0, 400.0}}) {
    const double expected = ck::cumulative_number(p, a) - ck::cumulative_number(p, b);
    EXPECT_NEAR(integrate_differential(p, a, b), expected, 1e-8 * expected) << a << " " << b;
  }
  // Far beyond the last break the cumulative number is the single power law of slope -4.
  EXPECT_NEAR(ck::cumulative_number(p, 2000.0) / ck::cumulative_number(p, 1000.0), std::pow(2.0, -3.0),
              1e-12);
}

TEST(Population, NormalisationByNumberLarger) {
  const auto p = ck::normalised(ck::power_law_population(-4.0), 5.0, 42.0);
  EXPECT_NEAR(ck::cumulative_number(p, 5.0), 42.0, 1e-12);
}

TEST(Population, TableInterpolatesInLogLog) {
  const auto path =
      temp_file("pop.csv", "# test\ndiameter_km,cumulative_number\n0.001,1e9\n0.01,1e6\n0.1,1e4\n");
  const auto toml =
      temp_file("pop.toml", "name = \"t\"\nkind = \"table\"\ntable = \"" + path.filename().string() + "\"\n");
  const auto p = ck::load_population_file(toml);
  // Knots (radius = diameter/2 in m).
  EXPECT_NEAR(ck::cumulative_number(p, 0.5), 1e9, 1e-3);
  EXPECT_NEAR(ck::cumulative_number(p, 5.0), 1e6, 1e-6);
  // Between knots: power law of log slope -3 (first segment) and -2 (second).
  EXPECT_NEAR(ck::cumulative_number(p, 0.5 * std::sqrt(10.0)), 1e9 * std::pow(10.0, -1.5), 1e-3);
  EXPECT_NEAR(ck::differential_number(p, 20.0), 2.0 * ck::cumulative_number(p, 20.0) / 20.0, 1e-9);
  EXPECT_NEAR(integrate_differential(p, 1.0, 40.0),
              ck::cumulative_number(p, 1.0) - ck::cumulative_number(p, 40.0),
              1e-7 * ck::cumulative_number(p, 1.0));
  // Outside the table: an error, not an extrapolation.
  EXPECT_THROW(ck::cumulative_number(p, 0.1), craterkit::InputError);
  EXPECT_THROW(ck::cumulative_number(p, 100.0), craterkit::InputError);
}

TEST(Population, MalformedTableNamesTheLine) {
  const auto path = temp_file("bad.csv", "diameter_km,cumulative_number\n0.001,1e9\n0.01,abc\n");
  const auto toml = temp_file("bad.toml", "kind = \"table\"\ntable = \"" + path.filename().string() + "\"\n");
  try {
    ck::load_population_file(toml);
    FAIL() << "expected InputError";
  } catch (const craterkit::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("abc"), std::string::npos) << e.what();
  }
  const auto unknown = temp_file("unk.toml",
                                 "kind = \"power_law\"\nslope = -4\nreference_diameter_km = 1\n"
                                 "number_larger = 1\nslop = 3\n");
  try {
    ck::load_population_file(unknown);
    FAIL() << "expected InputError";
  } catch (const craterkit::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown key slop"), std::string::npos) << e.what();
  }
}

TEST(Population, ShippedMainBeltPopulationIsConsistent) {
  const auto names = ck::population_names();
  ASSERT_FALSE(names.empty());
  for (const auto& name : names) {
    const auto p = ck::load_population(name);
    EXPECT_FALSE(p.citation.empty()) << name;
    const double a_lo = std::max(ck::minimum_radius(p), 0.01) * 1.01;
    const double a_hi = std::min(ck::maximum_radius(p), 1e5) * 0.99;
    const double expected = ck::cumulative_number(p, a_lo) - ck::cumulative_number(p, a_hi);
    EXPECT_NEAR(integrate_differential(p, a_lo, a_hi), expected, 1e-6 * expected) << name;
  }
}

TEST(Population, ApproximateFlagIsReadAndChecked) {
  // The shipped main-belt table is an approximation, and says so in a key the CLI warns about.
  EXPECT_TRUE(ck::load_population("main_belt_approx_bottke2005").approximate);
  const auto exact = temp_file(
      "exact.toml", "kind = \"power_law\"\nslope = -4\nreference_diameter_km = 1\nnumber_larger = 1\n");
  EXPECT_FALSE(ck::load_population_file(exact).approximate);
  const auto wrong = temp_file("approx_wrong.toml",
                               "kind = \"power_law\"\nslope = -4\nreference_diameter_km = 1\n"
                               "number_larger = 1\napproximate = \"yes\"\n");
  try {
    ck::load_population_file(wrong);
    FAIL() << "expected InputError";
  } catch (const craterkit::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(": approximate: expected true or false"), std::string::npos)
        << e.what();
  }
}
