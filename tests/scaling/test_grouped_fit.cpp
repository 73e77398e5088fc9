// Fits per group of a sweep-style table (grouped_fit.hpp): each group's constants recovered from synthetic
// radii made with known, different constants per friction; one fit with group_by none; pooled columns;
// regimes of rows far inside each regime; rows whose growth had not ended, flagged or left out; groups
// too small to fit; the grouped JSON and choosing a group's law from it.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/fit_json.hpp"
#include "craterkit/scaling/grouped_fit.hpp"

namespace cs = craterkit::scaling;

namespace {

constexpr double kNoise = 0.05;  // standard deviation of ln R

struct GroupTruth {
  std::string friction;
  cs::ScalingLaw law;
};

// Two frictions with different H1 and mu (HH2011 form; nu = 0.4 in both, fixed in the fits, since a sweep
// of one impactor density cannot determine it).
std::vector<GroupTruth> two_frictions() {
  return {{"0.55", {cs::Form::hh2011, 0.60, 0.25, 0.44, 0.4}},
          {"0.8", {cs::Form::hh2011, 0.75, 0.30, 0.40, 0.4}}};
}

struct SweepGrid {
  std::vector<double> masses{0.05, 0.5, 2.0, 20.0, 100.0, 2000.0};  // kg
  std::vector<double> cohesions{0.0, 0.05, 0.5, 5.0, 50.0};         // Pa
  std::vector<std::string> resolutions{"18"};
};

// A sweep-style CSV: per friction, resolution, mass and cohesion one row with radius law * exp(kNoise
// N(0,1)), sigma kNoise R, the run's name and growth_ended = !not_ended(friction, mass, cohesion).
std::string sweep_csv(
    const std::vector<GroupTruth>& groups, const SweepGrid& grid, unsigned seed,
    const std::function<bool(const std::string&, double, double)>& not_ended = [](const std::string&, double,
                                                                                  double) { return false; }) {
  std::mt19937_64 random(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::ostringstream out;
  out.precision(17);
  out << "# study test, synthetic\n"
      << "impactor_radius,impactor_density,velocity,target_density,gravity,strength,crater_radius,"
         "crater_radius_sigma,friction,porosity,resolution,run,growth_ended\n";
  const double delta = 2700.0;
  for (const auto& group : groups) {
    for (const auto& resolution : grid.resolutions) {
      for (double mass : grid.masses) {
        for (double y : grid.cohesions) {
          const cs::Impactor impactor{std::cbrt(3.0 * mass / (4.0 * std::numbers::pi * delta)), delta,
                                      2000.0};
          const cs::Target target{1300.0, 1.4e-4, y};
          const double r = cs::crater_radius(group.law, impactor, target) * std::exp(kNoise * normal(random));
          out << impactor.radius << "," << delta << ",2000,1300,1.4e-4," << y << "," << r << "," << kNoise * r
              << "," << group.friction << ",0.5," << resolution << ",m" << mass << "_y" << y << ","
              << (not_ended(group.friction, mass, y) ? "false" : "true") << "\n";
        }
      }
    }
  }
  return out.str();
}

cs::RadiiTable parse(const std::string& text) {
  std::istringstream in(text);
  return cs::parse_radii_csv(in, "sweep.csv");
}

cs::GroupedFitOptions hh_fixed_nu() {
  cs::GroupedFitOptions options;
  options.fit.form = cs::Form::hh2011;
  options.fit.fixed = {{"nu", 0.4}};
  return options;
}

double truth_value(const cs::ScalingLaw& law, const std::string& name) {
  if (name == "mu") return law.mu;
  if (name == "nu") return law.nu;
  return name.back() == '1' ? law.coefficient_1 : law.coefficient_2;
}

std::string error_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const craterkit::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(GroupedFit, RecoversEachGroupsConstants) {
  // One seeded realisation per group; within 2 sigma, as the single-fit tests (test_fit.cpp) check, whose
  // Monte Carlo coverage test shows that the sigmas are right. Seed 1 is the first seed tried.
  const auto table = parse(sweep_csv(two_frictions(), SweepGrid{}, 1));
  const auto result = cs::fit_groups(table, hh_fixed_nu());
  ASSERT_TRUE(result.grouped());
  EXPECT_EQ(result.group_by, (std::vector<std::string>{"friction", "porosity", "resolution"}));
  ASSERT_EQ(result.groups.size(), 2u);
  const auto truths = two_frictions();
  for (std::size_t g = 0; g < 2; ++g) {
    const auto& group = result.groups[g];
    const auto& truth = truths[g];
    SCOPED_TRACE(truth.friction);
    EXPECT_EQ(group.key.front(), (std::pair<std::string, std::string>{"friction", truth.friction}));
    EXPECT_EQ(group.lines.size(), 30u);
    EXPECT_EQ(group.cohesions, 5);
    ASSERT_TRUE(group.fit.has_value());
    for (const auto& p : group.fit->parameters) {
      SCOPED_TRACE(p.name);
      if (p.name == "nu") {
        EXPECT_TRUE(p.fixed);
        continue;
      }
      ASSERT_TRUE(p.determined);
      EXPECT_LT(std::abs(p.value - truth_value(truth.law, p.name)), 2.0 * p.sigma)
          << p.value << " +- " << p.sigma << " vs " << truth_value(truth.law, p.name);
    }
    EXPECT_EQ(group.fit->dof, 30 - 3);
    const auto& counts = group.regime_counts;
    EXPECT_EQ(counts.gravity + counts.transitional + counts.strength, 30);
  }
  // The two groups' mu differ (0.44 against 0.40) by many sigmas: the fits did not mix the groups.
  const auto& mu_a = result.groups[0].fit->parameter("mu");
  const auto& mu_b = result.groups[1].fit->parameter("mu");
  EXPECT_GT(std::abs(mu_a.value - mu_b.value), 2.0 * std::hypot(mu_a.sigma, mu_b.sigma));
}

TEST(GroupedFit, GroupByNoneGivesOneFitOverEveryRow) {
  const auto table = parse(sweep_csv(two_frictions(), SweepGrid{}, 2));
  auto options = hh_fixed_nu();
  options.group_by = std::vector<std::string>{};
  const auto result = cs::fit_groups(table, options);
  EXPECT_FALSE(result.grouped());
  ASSERT_EQ(result.groups.size(), 1u);
  EXPECT_EQ(result.groups[0].lines.size(), 60u);
  EXPECT_EQ(cs::describe(result.groups[0].key), "all rows");
  // Exactly the single fit of the whole table.
  const auto single = cs::fit_scaling_law(table, options.fit);
  EXPECT_EQ(cs::fit_to_json(result.groups[0].fit.value()).dump(), cs::fit_to_json(single).dump());
  ASSERT_EQ(result.pooled.size(), 3u);
  EXPECT_EQ(result.pooled[0].name, "friction");
  EXPECT_EQ(result.pooled[0].values, (std::vector<std::string>{"0.55", "0.8"}));
}

TEST(GroupedFit, GroupBySomeColumnsFitsTheOthersTogether) {
  SweepGrid grid;
  grid.resolutions = {"18", "24"};
  const auto table = parse(sweep_csv(two_frictions(), grid, 3));
  auto options = hh_fixed_nu();
  options.group_by = std::vector<std::string>{"friction"};
  const auto result = cs::fit_groups(table, options);
  ASSERT_EQ(result.groups.size(), 2u);
  EXPECT_EQ(result.groups[0].lines.size(), 60u);  // both resolutions
  ASSERT_EQ(result.pooled.size(), 2u);
  EXPECT_EQ(result.pooled[1].name, "resolution");
  EXPECT_EQ(result.pooled[1].values, (std::vector<std::string>{"18", "24"}));
  // By default every grouping column splits: 4 groups.
  EXPECT_EQ(cs::fit_groups(table, hh_fixed_nu()).groups.size(), 4u);
  // Names that are not grouping columns, or repeated, are errors naming them.
  options.group_by = std::vector<std::string>{"frictoin"};
  const std::string message = error_of([&] { cs::fit_groups(table, options); });
  EXPECT_NE(message.find("'frictoin'"), std::string::npos) << message;
  EXPECT_NE(message.find("friction, porosity, resolution"), std::string::npos) << message;
  options.group_by = std::vector<std::string>{"friction", "friction"};
  EXPECT_THROW(cs::fit_groups(table, options), craterkit::InputError);
}

TEST(GroupedFit, RowsFarInsideARegimeAreClassifiedSo) {
  SweepGrid grid;
  grid.masses = {0.05, 2.0, 2000.0, 1e5};
  grid.cohesions = {0.0, 1e-6, 1e3, 1e4};  // none or negligible, and far above the gravity term
  const auto table = parse(sweep_csv({two_frictions().front()}, grid, 4));
  const auto result = cs::fit_groups(table, hh_fixed_nu());
  ASSERT_TRUE(result.groups.front().fit.has_value());
  const auto regimes = cs::row_regimes(table.rows, *result.groups.front().fit);
  ASSERT_EQ(regimes.size(), table.rows.size());
  for (std::size_t i = 0; i < regimes.size(); ++i) {
    const double y = table.rows[i].target.strength;
    SCOPED_TRACE(y);
    EXPECT_EQ(regimes[i].line, table.rows[i].line);
    EXPECT_EQ(regimes[i].run, table.rows[i].run);
    if (y <= 1e-6) {
      EXPECT_EQ(regimes[i].regime.kind, cs::RegimeKind::gravity);
      EXPECT_LT(regimes[i].strength_to_gravity, 1.0 / 9.0);
    } else {
      EXPECT_EQ(regimes[i].regime.kind, cs::RegimeKind::strength);
      EXPECT_GT(regimes[i].strength_to_gravity, 9.0);
    }
  }
  EXPECT_EQ(result.groups.front().regime_counts.gravity, 8);
  EXPECT_EQ(result.groups.front().regime_counts.strength, 8);
  EXPECT_EQ(result.groups.front().regime_counts.transitional, 0);
  EXPECT_DOUBLE_EQ(regimes.front().strength_to_gravity, 0.0);  // Y = 0: no strength term at all
}

TEST(GroupedFit, GrowthNotEndedIsFlaggedOrLeftOutExactly) {
  const auto not_ended = [](const std::string& friction, double mass, double y) {
    return (friction == "0.55" && mass == 2000.0 && y <= 0.05) ||
           (friction == "0.8" && mass == 100.0 && y == 0.0);
  };
  const auto table = parse(sweep_csv(two_frictions(), SweepGrid{}, 5, not_ended));
  std::set<int> flagged;
  for (const auto& row : table.rows) {
    if (row.growth_ended == false) flagged.insert(row.line);
  }
  ASSERT_EQ(flagged.size(), 3u);
  // Default: fitted and flagged.
  const auto kept = cs::fit_groups(table, hh_fixed_nu());
  EXPECT_TRUE(kept.excluded.empty());
  EXPECT_EQ(kept.groups[0].growth_not_ended.size() + kept.groups[1].growth_not_ended.size(), 3u);
  EXPECT_EQ(kept.groups[0].lines.size() + kept.groups[1].lines.size(), 60u);
  // --require-growth-ended: exactly the flagged rows are left out.
  auto options = hh_fixed_nu();
  options.require_growth_ended = true;
  const auto dropped = cs::fit_groups(table, options);
  EXPECT_EQ(std::set<int>(dropped.excluded.begin(), dropped.excluded.end()), flagged);
  std::size_t fitted_rows = 0;
  for (const auto& group : dropped.groups) {
    EXPECT_TRUE(group.growth_not_ended.empty());
    for (int line : group.lines) EXPECT_FALSE(flagged.contains(line)) << line;
    fitted_rows += group.lines.size();
    EXPECT_EQ(group.fit->residuals.size(), group.lines.size());
  }
  EXPECT_EQ(fitted_rows, 57u);
  const auto json = cs::grouped_fit_to_json(dropped);
  EXPECT_TRUE(json["excluded_rows"]["require_growth_ended"].get<bool>());
  EXPECT_EQ(json["excluded_rows"]["lines"].size(), 3u);
  // Without a growth_ended column the option is an error naming the column.
  const auto plain = parse(
      "impactor_radius,impactor_density,velocity,target_density,gravity,strength,"
      "crater_radius,friction\n0.05,2700,2000,1300,1.4e-4,0.05,7.2,0.5\n");
  const std::string message = error_of([&] { cs::fit_groups(plain, options); });
  EXPECT_NE(message.find("'growth_ended'"), std::string::npos) << message;
}

TEST(GroupedFit, GroupsTooSmallOrBlindAreReportedNotFatal) {
  // A third friction with 3 rows (3 free parameters): not fitted; a fourth with gravity-only rows: fitted,
  // with H2 undetermined. The others are fitted as usual.
  std::string text = sweep_csv(two_frictions(), SweepGrid{}, 6);
  SweepGrid small;
  small.masses = {2.0};
  small.cohesions = {0.05, 0.5, 5.0};
  const std::string extra = sweep_csv({{"0.3", two_frictions().front().law}}, small, 7);
  text += extra.substr(extra.find("growth_ended\n") + 13);
  SweepGrid gravity_only;
  gravity_only.cohesions = {0.0};
  const std::string blind = sweep_csv({{"0.2", two_frictions().front().law}}, gravity_only, 8);
  text += blind.substr(blind.find("growth_ended\n") + 13);
  const auto table = parse(text);
  const auto result = cs::fit_groups(table, hh_fixed_nu());
  ASSERT_EQ(result.groups.size(), 4u);
  EXPECT_TRUE(result.groups[0].fit && result.groups[1].fit);
  const auto& too_small = result.groups[2];
  EXPECT_FALSE(too_small.fit.has_value());
  EXPECT_NE(too_small.not_fitted.find("3 rows for 3 free parameters"), std::string::npos)
      << too_small.not_fitted;
  const auto& none = too_small.regime_counts;
  EXPECT_EQ(none.gravity + none.transitional + none.strength, 0);
  const auto& gravity = result.groups[3];
  ASSERT_TRUE(gravity.fit.has_value());
  EXPECT_EQ(gravity.cohesions, 1);
  EXPECT_FALSE(gravity.fit->parameter("H2").determined);
  const auto json = cs::grouped_fit_to_json(result);
  EXPECT_TRUE(json["groups"][2]["fit"].is_null());
  EXPECT_EQ(json["groups"][2]["not_fitted"], too_small.not_fitted);
  EXPECT_TRUE(json["groups"][3]["fit"]["parameters"]["H2"]["sigma"].is_null());
  // Choosing the unfitted group's law is an error that says why.
  const std::string message = error_of([&] { cs::fitted_law_from_json(json, "g.json", "friction=0.3"); });
  EXPECT_NE(message.find("was not fitted"), std::string::npos) << message;
}

TEST(GroupedFit, JsonHasOneEntryPerGroupAndGivesEachGroupsLaw) {
  const auto table = parse(sweep_csv(two_frictions(), SweepGrid{}, 1));
  const auto result = cs::fit_groups(table, hh_fixed_nu());
  const auto json = cs::grouped_fit_to_json(result);
  for (const auto* key : {"form", "group_by", "pooled", "rows_read", "excluded_rows", "notes", "groups"})
    EXPECT_TRUE(json.contains(key)) << key;
  ASSERT_EQ(json["groups"].size(), 2u);
  const auto& first = json["groups"][0];
  EXPECT_EQ(first["group"]["friction"], "0.55");
  EXPECT_EQ(first["group"]["resolution"], "18");
  EXPECT_EQ(first["rows"], 30);
  EXPECT_EQ(first["fit"].dump(), cs::fit_to_json(*result.groups[0].fit).dump());
  EXPECT_FALSE(first.contains("regimes"));  // per row only in the residuals CSV
  const int counted = first["regime_counts"]["gravity"].get<int>() +
                      first["regime_counts"]["transitional"].get<int>() +
                      first["regime_counts"]["strength"].get<int>();
  EXPECT_EQ(counted, 30);

  // Each group's law and covariance back from the JSON, by a full or a partial key.
  const auto law = cs::fitted_law_from_json(json, "g.json", "friction=0.8");
  const auto& fit = *result.groups[1].fit;
  EXPECT_DOUBLE_EQ(law.law.coefficient_1, fit.law().coefficient_1);
  EXPECT_DOUBLE_EQ(law.law.mu, fit.law().mu);
  EXPECT_EQ(law.group.size(), 3u);
  const auto expected = cs::law_covariance(fit);
  ASSERT_EQ(law.covariance.names, expected.names);
  EXPECT_EQ(law.covariance.fixed, (std::vector<std::string>{"nu"}));
  EXPECT_LT((law.covariance.covariance - expected.covariance).norm(), 1e-12 * expected.covariance.norm());
  EXPECT_DOUBLE_EQ(
      cs::fitted_law_from_json(json, "g.json", "friction=0.55,porosity=0.5,resolution=18").law.coefficient_2,
      result.groups[0].fit->law().coefficient_2);

  // Without --group, or with one that picks none or several, the error lists the groups.
  for (const std::optional<std::string>& group :
       {std::optional<std::string>{}, std::optional<std::string>{"friction=0.6"},
        std::optional<std::string>{"porosity=0.5"}}) {
    const std::string message = error_of([&] { cs::fitted_law_from_json(json, "g.json", group); });
    EXPECT_NE(message.find("friction=0.55,porosity=0.5,resolution=18"), std::string::npos) << message;
    EXPECT_NE(message.find("friction=0.8,porosity=0.5,resolution=18"), std::string::npos) << message;
  }
  EXPECT_NE(error_of([&] { cs::fitted_law_from_json(json, "g.json", "colour=red"); }).find("'colour'"),
            std::string::npos);
  EXPECT_THROW(cs::fitted_law_from_json(json, "g.json", "friction"), craterkit::InputError);
  // A single fit takes no group.
  const auto single = cs::fit_to_json(*result.groups[0].fit);
  EXPECT_THROW(cs::fitted_law_from_json(single, "f.json", "friction=0.55"), craterkit::InputError);
  EXPECT_TRUE(cs::fitted_law_from_json(single, "f.json").covariance.has_covariance());
}

// --residuals: one CSV line per fitted row, in group order, with the row's residuals as the fit computed them
// (read back exactly) and its regime; the model radius is the group's law at the row. Rows left out and
// groups not fitted are not listed.
TEST(GroupedFit, ResidualsCsvListsEveryFittedRowWithItsRegime) {
  const auto not_ended = [](const std::string& friction, double mass, double y) {
    return friction == "0.8" && mass == 2.0 && y > 1.0;
  };
  const auto table = parse(sweep_csv(two_frictions(), SweepGrid{}, 1, not_ended));
  auto options = hh_fixed_nu();
  options.group_by = std::vector<std::string>{"friction"};
  options.require_growth_ended = true;
  const auto result = cs::fit_groups(table, options);
  ASSERT_EQ(result.excluded.size(), 2u);
  std::ostringstream out;
  cs::write_residuals_csv(out, table, result);
  std::istringstream in(out.str());
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line,
            "friction,line,run,growth_ended,observed,model,log_residual,normalized,regime,gravity_share,"
            "strength_to_gravity");
  std::size_t rows = 0;
  for (const auto& group : result.groups) {
    ASSERT_TRUE(group.fit.has_value());
    for (std::size_t k = 0; k < group.rows.size(); ++k, ++rows) {
      ASSERT_TRUE(std::getline(in, line)) << "row " << rows;
      std::vector<std::string> cells;
      std::stringstream split(line);
      for (std::string cell; std::getline(split, cell, ',');) cells.push_back(cell);
      if (!line.empty() && line.back() == ',') cells.emplace_back();
      ASSERT_EQ(cells.size(), 11u) << line;
      const auto& row = table.rows[group.rows[k]];
      const auto& r = group.fit->residuals[k];
      EXPECT_EQ(cells[0], group.key.front().second);
      EXPECT_EQ(std::stoi(cells[1]), row.line);
      EXPECT_EQ(cells[2], row.run.value());
      EXPECT_EQ(cells[3], "true");
      EXPECT_EQ(std::stod(cells[4]), row.crater_radius);
      EXPECT_EQ(std::stod(cells[5]), r.model);
      EXPECT_EQ(std::stod(cells[6]), r.log_residual);
      EXPECT_EQ(std::stod(cells[7]), r.normalized);
      const double model = cs::crater_radius(group.fit->law(), row.impactor, row.target);
      EXPECT_NEAR(std::stod(cells[5]), model, 1e-12 * model);
      EXPECT_NEAR(std::stod(cells[6]), std::log(model / row.crater_radius), 1e-12);
      EXPECT_NEAR(std::stod(cells[7]), std::stod(cells[6]) / (*row.crater_radius_sigma / row.crater_radius),
                  1e-9);
      const auto regime = cs::row_regime(row, *group.fit);
      EXPECT_EQ(cells[8], cs::to_string(regime.regime.kind));
      EXPECT_EQ(std::stod(cells[9]), regime.regime.gravity_share);
      if (std::isfinite(regime.strength_to_gravity)) {
        EXPECT_EQ(std::stod(cells[10]), regime.strength_to_gravity);
      } else {
        EXPECT_EQ(cells[10], "");
      }
    }
  }
  EXPECT_EQ(rows, table.rows.size() - 2);
  EXPECT_FALSE(std::getline(in, line)) << "a line too many: " << line;

  // Without the rows' residuals there is nothing to write.
  options.fit.keep_residuals = false;
  std::ostringstream lean;
  EXPECT_THROW(cs::write_residuals_csv(lean, table, cs::fit_groups(table, options)), std::logic_error);
}

TEST(GroupedFit, OneNumberWrittenTwoWaysIsNoted) {
  std::string text = sweep_csv(two_frictions(), SweepGrid{}, 9);
  std::size_t at = 0;
  for (int k = 0; k < 3; ++k) at = text.find(",0.8,0.5,18,", at + 1);  // the third row of friction 0.8
  text.replace(at, 12, ",0.80,0.5,18,");
  const auto result = cs::fit_groups(parse(text), hh_fixed_nu());
  EXPECT_EQ(result.groups.size(), 3u);  // "0.80" is a group of its own
  ASSERT_EQ(result.notes.size(), 1u);
  EXPECT_NE(result.notes[0].find("'0.8' and '0.80'"), std::string::npos) << result.notes[0];
  EXPECT_FALSE(result.groups[2].fit.has_value());  // one row
}
