// The plan of a study: the sizing rule against hand-computed values, the material axes written into a copy
// of the target material, the configurations parsed before anything runs, and every class of study that
// only the plan can reject (materials, the base, duplicates, values the configuration refuses).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <ostream>

#include "craterkit/common/data_path.hpp"
#include "craterkit/impact/impact_config.hpp"
#include "craterkit/scaling/constant_sets.hpp"
#include "craterkit/study/material_axes.hpp"
#include "craterkit/study/study_plan.hpp"
#include "study_test_helpers.hpp"

using namespace craterkit;
using namespace craterkit::study;
using namespace craterkit::study::test;

namespace {

StudyPlan plan(const Scratch& scratch, const std::string& text, const char* base = tiny_base()) {
  scratch.write("base.toml", base);
  const auto file = scratch.write("study.toml", text);
  return plan_study(load_study(file), scratch.path() / "out");
}

impact::ImpactConfig parsed(const PlannedRun& run) {
  return impact::parse_impact_config(run.config_text, run.name);
}

// The crater radius of the Housen & Holsapple (2011) form in the gravity regime, written out:
// pi_R = H1 pi4^((2 + mu - 6 nu) / (3 (2 + mu))) pi2^(-mu / (2 + mu)), R = pi_R (m / rho)^(1/3).
double gravity_regime_radius(double mass, double delta, double U, double rho, double g) {
  const double H1 = 0.60, mu = 0.44, nu = 0.4;
  const double a = std::cbrt(3.0 * mass / (4.0 * std::numbers::pi * delta));
  const double pi2 = g * a / (U * U), pi4 = rho / delta;
  const double pi_R =
      H1 * std::pow(pi4, (2.0 + mu - 6.0 * nu) / (3.0 * (2.0 + mu))) * std::pow(pi2, -mu / (2.0 + mu));
  return pi_R * std::cbrt(mass / rho);
}

}  // namespace

TEST(StudyPlan, SizingRuleAgainstHandComputedValues) {
  Scratch scratch;
  const StudyPlan p = plan(scratch, R"([study]
base = "sci.toml"
law = "jutzi2022_ryugu"
[grid]
projectile_mass = [2.0, 0.05, 2000]
cohesion = [0.0, 0.5]
[[runs]]
projectile_mass = 2.0
t_transition = 0.2
)");
  ASSERT_EQ(p.runs.size(), 7u);
  const double g = 1.4e-4, U = 2000.0, delta = 2700.0, rho = 2600.0 / 2.0;
  for (const double mass : {2.0, 0.05, 2000.0}) {
    const PlannedRun& run = p.runs[mass == 2.0 ? 0 : mass == 0.05 ? 2 : 4];
    SCOPED_TRACE(run.name);
    const double a = std::cbrt(3.0 * mass / (4.0 * std::numbers::pi * delta));
    const double R = gravity_regime_radius(mass, delta, U, rho, g);
    EXPECT_NEAR(run.sizing.predicted_crater_radius, R, 1e-12 * R);
    EXPECT_DOUBLE_EQ(run.sizing.projectile_radius, a);
    EXPECT_DOUBLE_EQ(run.sizing.domain_radius, 15.0 / 8.91 * R);
    EXPECT_DOUBLE_EQ(run.sizing.particle_spacing, R / (8.91 / 0.5));
    EXPECT_DOUBLE_EQ(run.sizing.inner_spacing, 0.5 * a);
    EXPECT_DOUBLE_EQ(run.sizing.end_time, 2.0 * std::sqrt(R / g));
    EXPECT_TRUE(run.sized);
    // The configuration holds exactly these values, and the base's other keys.
    const auto config = parsed(run);
    EXPECT_EQ(config.impact.domain_radius, run.sizing.domain_radius);
    EXPECT_EQ(config.impact.particle_spacing, run.sizing.particle_spacing);
    EXPECT_EQ(config.impact.inner_spacing, run.sizing.inner_spacing);
    EXPECT_EQ(config.simulation.run.end_time, run.sizing.end_time);
    EXPECT_EQ(config.impact.transition_time, 0.0);  // the default rule 10 R_dom / c
    EXPECT_EQ(config.impact.grading, 0.1);
    EXPECT_EQ(config.impact.projectile_mass, mass);
    EXPECT_EQ(config.simulation.name, run.name);
    // The same number of spacings across every run's predicted crater.
    EXPECT_DOUBLE_EQ(run.resolution, 8.91 / 0.5);
  }
  // The published example: R_pred = 8.91 m for SCI (docs/impact_setup.md "Examples"), so the SCI domain.
  EXPECT_NEAR(p.runs[0].sizing.predicted_crater_radius, 8.91, 0.005);
  EXPECT_NEAR(p.runs[0].sizing.domain_radius, 15.0, 0.01);
  EXPECT_NEAR(p.runs[0].sizing.particle_spacing, 0.5, 0.001);
  EXPECT_NEAR(p.runs[2].sizing.predicted_crater_radius, 3.25, 0.005);
  EXPECT_NEAR(p.runs[4].sizing.predicted_crater_radius, 58.8, 0.05);
  // With cohesion: the strength term of the law, Y = the run's cohesion.
  const auto law = scaling::load_constant_set("jutzi2022_ryugu").law;
  const PlannedRun& strong = p.runs[1];
  EXPECT_EQ(strong.cohesion, 0.5);
  const double R = scaling::crater_radius(law, {strong.sizing.projectile_radius, delta, U}, {rho, g, 0.5});
  EXPECT_DOUBLE_EQ(strong.sizing.predicted_crater_radius, R);
  EXPECT_LT(R, p.runs[0].sizing.predicted_crater_radius);
  EXPECT_DOUBLE_EQ(strong.sizing.domain_radius, 15.0 / 8.91 * R);
  // t_transition stays the engine's rule unless an axis sets it.
  EXPECT_EQ(parsed(p.runs[6]).impact.transition_time, 0.2);
  EXPECT_EQ(p.extra_columns, std::vector<std::string>{"t_transition"});
  EXPECT_EQ(p.runs[0].extra_cells, std::vector<std::string>{""});  // filled from the run's summary
  EXPECT_EQ(p.runs[6].extra_cells, std::vector<std::string>{"0.20000000000000001"});
}

TEST(StudyPlan, ThePredictionMayLeaveTheCohesionOut) {
  Scratch scratch;
  const StudyPlan p = plan(scratch,
                           "[study]\nbase = \"sci\"\n[sizing]\npredict_with_cohesion = false\n[grid]\n"
                           "cohesion = [0.0, 0.5]\n");
  EXPECT_EQ(p.runs[1].cohesion, 0.5);
  EXPECT_EQ(p.runs[1].sizing.predicted_crater_radius, p.runs[0].sizing.predicted_crater_radius);
  EXPECT_EQ(p.runs[1].sizing.domain_radius, p.runs[0].sizing.domain_radius);
  EXPECT_EQ(parsed(p.runs[1]).impact.domain_radius, parsed(p.runs[0]).impact.domain_radius);
}

TEST(StudyPlan, ResolutionAxisAndSizingConstants) {
  Scratch scratch;
  const StudyPlan p = plan(scratch, R"([study]
base = "sci"
[sizing]
domain_over_radius = 2.0
core_spacing_over_projectile_radius = 0.25
end_time_over_growth_time = 1.5
[grid]
resolution = [10, 20]
)");
  for (const auto& run : p.runs) {
    const double R = run.sizing.predicted_crater_radius;
    const double n = run.index == 0 ? 10.0 : 20.0;
    EXPECT_DOUBLE_EQ(run.sizing.particle_spacing, R / n);
    EXPECT_DOUBLE_EQ(run.sizing.domain_radius, 2.0 * R);
    EXPECT_DOUBLE_EQ(run.sizing.inner_spacing, 0.25 * run.sizing.projectile_radius);
    EXPECT_DOUBLE_EQ(run.sizing.end_time, 1.5 * std::sqrt(R / 1.4e-4));
    EXPECT_EQ(run.resolution, n);
  }
}

TEST(StudyPlan, WithoutSizingTheBaseSizesStay) {
  Scratch scratch;
  const StudyPlan p = plan(
      scratch, "[study]\nbase = \"base.toml\"\n[sizing]\nenabled = false\n[grid]\nimpact_speed = [50, 60]\n");
  for (const auto& run : p.runs) {
    const auto config = parsed(run);
    EXPECT_FALSE(run.sized);
    EXPECT_EQ(config.impact.domain_radius, 5.0);
    EXPECT_EQ(config.impact.particle_spacing, 0.5);
    EXPECT_EQ(config.impact.transition_time, 0.01);
    EXPECT_EQ(config.simulation.run.end_time, 0.3);
    EXPECT_DOUBLE_EQ(run.resolution, run.sizing.predicted_crater_radius / 0.5);
  }
  EXPECT_EQ(parsed(p.runs[1]).impact.impact_speed, 60.0);
  EXPECT_EQ(p.runs[1].velocity, 60.0);
  EXPECT_EQ(p.runs[1].gravity, 1.0);
  EXPECT_EQ(p.runs[1].impactor_density, 1300.0);
  EXPECT_DOUBLE_EQ(p.runs[1].impactor_radius, std::cbrt(3.0 * 5450.0 / (4.0 * std::numbers::pi * 1300.0)));
  EXPECT_FALSE(p.runs[0].target_text);  // no material axis: the shipped material by name
  EXPECT_EQ(p.runs[0].target_material, "basalt_matrix_ryugu");
  EXPECT_EQ(p.runs[0].friction, 0.55);
  EXPECT_EQ(p.runs[0].porosity, 0.5);
  EXPECT_EQ(p.runs[0].bulk_density, 1300.0);
}

TEST(StudyPlan, MaterialAxesGoIntoACopyOfTheTargetMaterial) {
  Scratch scratch;
  const auto shipped = data_file("materials/basalt_matrix_ryugu.toml");
  const std::string before = read(shipped);
  const StudyPlan p = plan(scratch, R"([study]
base = "base.toml"
[sizing]
enabled = false
[[runs]]
angle_of_repose = 30
[[runs]]
friction = 0.4
cohesion = 5
[[runs]]
porosity = 0.6
[[runs]]
cohesion = 10
"target.strength.limiting_strength" = 1e6
[[runs]]
projectile_radius = 1.2
)");
  EXPECT_EQ(read(shipped), before);
  const double f30 = 2.0 * std::sqrt(2.0) * 0.5 / (3.0 - 0.5);
  EXPECT_DOUBLE_EQ(friction_from_angle_of_repose(30.0), f30);
  EXPECT_DOUBLE_EQ(distention_from_porosity(0.6), 2.5);
  const auto& angle = p.runs[0];
  ASSERT_TRUE(angle.target_text);
  EXPECT_DOUBLE_EQ(angle.friction, f30);
  const auto dir = scratch.path() / "out" / "runs" / angle.name;
  EXPECT_EQ(angle.target_material, (dir / "target.toml").string());
  EXPECT_NE(angle.config_text.find("target_material = \"" + (dir / "target.toml").string() + "\""),
            std::string::npos);
  EXPECT_NE(angle.target_text->find("friction_coefficient = 0.565685424949238"), std::string::npos)
      << *angle.target_text;
  EXPECT_EQ(p.runs[1].friction, 0.4);
  EXPECT_EQ(p.runs[1].cohesion, 5.0);
  EXPECT_NE(p.runs[1].target_text->find("cohesion = 5.0"), std::string::npos);
  EXPECT_EQ(p.runs[2].initial_distention, 2.5);
  EXPECT_DOUBLE_EQ(p.runs[2].porosity, 0.6);
  EXPECT_DOUBLE_EQ(p.runs[2].bulk_density, 2600.0 / 2.5);
  EXPECT_NE(p.runs[2].target_text->find("initial_distention = 2.5"), std::string::npos);
  EXPECT_NE(p.runs[3].target_text->find("limiting_strength = 1e+06"), std::string::npos);
  EXPECT_EQ(p.extra_columns, std::vector<std::string>{"target.strength.limiting_strength"});
  EXPECT_EQ(p.runs[3].extra_cells, std::vector<std::string>{"1000000"});
  EXPECT_EQ(p.runs[0].extra_cells, std::vector<std::string>{"3500000000"});  // the material's own value
  // projectile_radius: the mass of that sphere at the base's projectile density.
  EXPECT_DOUBLE_EQ(parsed(p.runs[4]).impact.projectile_mass,
                   4.0 / 3.0 * std::numbers::pi * 1.2 * 1.2 * 1.2 * 1300.0);
  EXPECT_DOUBLE_EQ(p.runs[4].impactor_radius, 1.2);
}

TEST(StudyPlan, AMaterialGivenByPathAndByRepose) {
  Scratch scratch;
  // A material next to the base, with its friction given as a repose angle: the friction axis replaces it.
  std::string material = read(data_file("materials/basalt_matrix_ryugu.toml"));
  material.replace(material.find("friction_coefficient = 0.55"), 27, "repose_angle_degrees = 35.0");
  scratch.write("materials/mine.toml", material);
  std::string base = tiny_base();
  base.replace(base.find("[impact]\n"), 9, "[impact]\ntarget_material = \"materials/mine.toml\"\n");
  const StudyPlan p = plan(scratch,
                           "[study]\nbase = \"base.toml\"\n[sizing]\nenabled = false\n[grid]\nfriction = "
                           "[0.3]\ncohesion = [1.0]\n[[runs]]\n",
                           base.c_str());
  ASSERT_EQ(p.runs.size(), 2u);
  EXPECT_EQ(p.runs[0].target_text->find("repose_angle_degrees"), std::string::npos);
  EXPECT_EQ(p.runs[0].friction, 0.3);
  // The unchanged run names the material by its absolute path.
  EXPECT_EQ(p.runs[1].target_material, (scratch.path() / "materials/mine.toml").string());
  EXPECT_DOUBLE_EQ(p.runs[1].friction, friction_from_angle_of_repose(35.0));
}

struct BadPlan {
  std::string what;
  std::string text;
  std::vector<std::string> expected;
};

// GoogleTest names each case by what it tests instead of printing the struct's bytes.
void PrintTo(const BadPlan& bad, std::ostream* out) {
  *out << bad.what;
}

class StudyPlanRejects : public ::testing::TestWithParam<BadPlan> {};

TEST_P(StudyPlanRejects, BeforeAnyRunNamingTheKey) {
  Scratch scratch;
  const auto& bad = GetParam();
  const std::string message = input_error([&] { plan(scratch, bad.text); });
  for (const auto& part : bad.expected)
    EXPECT_NE(message.find(part), std::string::npos) << bad.what << ": " << message;
  EXPECT_FALSE(std::filesystem::exists(scratch.path() / "out")) << "the plan wrote something";
}

INSTANTIATE_TEST_SUITE_P(
    All, StudyPlanRejects,
    ::testing::Values(
        BadPlan{"porosity below the crush curve's transition",
                "[study]\nbase = \"base.toml\"\n[sizing]\nenabled = false\n[grid]\nporosity = [0.5, 0.1]\n",
                {"grid.porosity", "0.1", "transition_distention", "(0.2, 1)"}},
        BadPlan{"unknown material",
                "[study]\nbase = \"base.toml\"\n[sizing]\nenabled = "
                "false\n[[runs]]\n\"impact.target_material\" = \"unobtainium\"\n",
                {"runs[0]", "impact.target_material", "unobtainium"}},
        BadPlan{"cohesion of a material without strength",
                "[study]\nbase = \"base.toml\"\n[sizing]\nenabled = "
                "false\n[[runs]]\n\"impact.target_material\" = \"basalt\"\ncohesion = 1.0\n",
                {"runs[0].cohesion", "Lundborg"}},
        BadPlan{"porosity of a material without porosity",
                "[study]\nbase = \"base.toml\"\n[sizing]\nenabled = "
                "false\n[[runs]]\n\"impact.target_material\" = \"boulder\"\nporosity = 0.4\n",
                {"runs[0].porosity", "P-alpha"}},
        BadPlan{"a material value out of range",
                "[study]\nbase = \"base.toml\"\n[sizing]\nenabled = false\n[[runs]]\ncohesion = "
                "5.0\n\"target.strength.limiting_strength\" = 1.0\n",
                {"runs[0]", "limiting_strength"}},
        BadPlan{"a base that is not an impact",
                "[study]\nbase = \"sedov.toml\"\n[[runs]]\n",
                {"study.base", "sedov.toml", "impact"}},
        BadPlan{"duplicate runs",
                "[study]\nbase = \"base.toml\"\n[sizing]\nenabled = false\n[grid]\ncohesion = [0.1, "
                "0.2]\n[[runs]]\ncohesion = 0.2\n",
                {"runs[0]", "duplicate", "cohesion-0.2"}},
        BadPlan{"a run equal to the base",
                "[study]\nbase = \"base.toml\"\n[sizing]\nenabled = false\n[grid]\nimpact_speed = [50.0, "
                "70.0]\n[[runs]]\n",
                {"runs[0]", "duplicate", "impact_speed-50"}},
        BadPlan{
            "a configuration value the engine refuses",
            "[study]\nbase = \"base.toml\"\n[sizing]\nenabled = false\n[grid]\n\"impact.grading\" = [7.0]\n",
            {"grid run impact.grading-7", "impact.grading"}},
        BadPlan{"a key of a table that is a value",
                "[study]\nbase = \"base.toml\"\n[sizing]\nenabled = false\n[grid]\n\"impact.escape_speed.x\" "
                "= [1.0]\n",
                {"grid.impact.escape_speed.x", "not a table"}},
        BadPlan{"unknown law",
                "[study]\nbase = \"base.toml\"\nlaw = \"nolaw\"\n[[runs]]\n",
                {"study.law", "nolaw"}},
        BadPlan{"a core spacing above the outer spacing",
                "[study]\nbase = \"base.toml\"\n[[runs]]\n",
                {"runs[0]", "core spacing", "core_spacing_over_projectile_radius"}}),
    [](const ::testing::TestParamInfo<BadPlan>& param) {
      std::string name;
      for (const char c : param.param.what) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
      return name;
    });

TEST(StudyPlan, SizingNeedsGravity) {
  Scratch scratch;
  std::string base = tiny_base();
  base.replace(base.find("gravity = [0.0, 0.0, -1.0]"), 26, "gravity = [0.0, 0.0, 0.0]");
  const auto message =
      input_error([&] { plan(scratch, "[study]\nbase = \"base.toml\"\n[[runs]]\n", base.c_str()); });
  EXPECT_NE(message.find("sizing"), std::string::npos) << message;
}

TEST(StudyPlan, WritePlanLeavesEqualFilesAndRefusesAStartedRunOfAnotherStudy) {
  Scratch scratch;
  const std::string study =
      "[study]\nbase = \"base.toml\"\n[sizing]\nenabled = false\n[grid]\ncohesion = [0.0, 1.0]\n";
  const StudyPlan p = plan(scratch, study);
  write_plan(p, 1);  // an array task's: its own run only
  EXPECT_FALSE(std::filesystem::exists(scratch.path() / "out" / "runs" / "cohesion-0"));
  EXPECT_TRUE(std::filesystem::exists(scratch.path() / "out" / "runs" / "cohesion-1" / "config.toml"));
  EXPECT_TRUE(std::filesystem::exists(scratch.path() / "out" / "sweep.json"));
  write_plan(p);
  const auto dir = scratch.path() / "out" / "runs" / "cohesion-0";
  for (const char* name : {"config.toml", "target.toml", "run.json"})
    EXPECT_TRUE(std::filesystem::exists(dir / name));
  EXPECT_EQ(read(dir / "config.toml"), p.runs[0].config_text);
  EXPECT_EQ(read(dir / "target.toml"), *p.runs[0].target_text);
  EXPECT_NE(read(scratch.path() / "out" / "sweep.json").find("\"cohesion-1\""), std::string::npos);
  const auto stamp = std::filesystem::last_write_time(dir / "config.toml");
  write_plan(plan(scratch, study));
  EXPECT_EQ(std::filesystem::last_write_time(dir / "config.toml"), stamp);

  // The base changes: a run that has not started is rewritten; one that has started is refused.
  std::string base = tiny_base();
  base.replace(base.find("end_time = 0.3"), 14, "end_time = 0.4");
  const StudyPlan changed = plan(scratch, study, base.c_str());
  write_plan(changed);
  EXPECT_EQ(read(dir / "config.toml"), changed.runs[0].config_text);
  std::ofstream(dir / "attempts.log") << "attempt 1\n";
  const StudyPlan again = plan(scratch, study);
  const auto message = input_error([&] { write_plan(again); });
  EXPECT_NE(message.find("cohesion-0"), std::string::npos) << message;
  EXPECT_EQ(read(dir / "config.toml"), changed.runs[0].config_text);
  EXPECT_EQ(read(scratch.path() / "out/runs/cohesion-1/config.toml"), changed.runs[1].config_text);
}

TEST(StudyPlan, TheShippedExampleStudyPlans) {
  const auto file = data_file("studies/example.toml");
  const Study study = load_study(file);
  Scratch scratch;
  const StudyPlan p = plan_study(study, scratch.path() / "out");
  EXPECT_EQ(p.runs.size(), 4u);
  for (const auto& run : p.runs) {
    EXPECT_TRUE(run.sized) << run.name;
    EXPECT_NO_THROW(parsed(run)) << run.name;
  }
}

// Every study shipped in data/studies (each file with a [study] table; example_base.toml is a base) plans,
// and each of its runs is a configuration the engine parses, so that no shipped study is refused when run.
TEST(StudyPlan, EveryShippedStudyPlans) {
  std::size_t studies = 0;
  for (const auto& entry : std::filesystem::directory_iterator(data_file("studies"))) {
    if (entry.path().extension() != ".toml") continue;
    if (read(entry.path()).find("[study]") == std::string::npos) continue;
    const Study study = load_study(entry.path());
    Scratch scratch;
    const StudyPlan p = plan_study(study, scratch.path() / "out");
    EXPECT_FALSE(p.runs.empty()) << entry.path();
    for (const auto& run : p.runs) EXPECT_NO_THROW(parsed(run)) << entry.path() << ": " << run.name;
    ++studies;
  }
  EXPECT_GE(studies, 5u);  // example, main_job, the two coarse studies, sci_trends
}

TEST(StudyPlan, ConfigurationKeysComeFirstAndTheirCellsAreAsGiven) {
  Scratch scratch;
  const StudyPlan p = plan(scratch, R"([study]
base = "base.toml"
[sizing]
enabled = false
[[runs]]
projectile_radius = 1.1
"impact.projectile_density" = 2000.0
[[runs]]
"impact.target_material" = "boulder"
friction = 0.9
)");
  // The radius axis comes first in the file, but the mass is that of a 1.1 m sphere of the run's density.
  EXPECT_DOUBLE_EQ(parsed(p.runs[0]).impact.projectile_mass,
                   4.0 / 3.0 * std::numbers::pi * 1.1 * 1.1 * 1.1 * 2000.0);
  EXPECT_DOUBLE_EQ(p.runs[0].impactor_radius, 1.1);
  EXPECT_EQ(p.runs[0].impactor_density, 2000.0);
  EXPECT_EQ(p.extra_columns,
            (std::vector<std::string>{"impact.projectile_density", "impact.target_material"}));
  EXPECT_EQ(p.runs[0].extra_cells, (std::vector<std::string>{"2000", ""}));
  // The material column holds the material as the study names it, not the copy in the run's folder.
  EXPECT_EQ(p.runs[1].extra_cells, (std::vector<std::string>{"1300", "boulder"}));
  EXPECT_NE(p.runs[1].target_material.find("target.toml"), std::string::npos);
  EXPECT_EQ(p.runs[1].friction, 0.9);
  EXPECT_EQ(p.runs[1].porosity, 0.0);  // boulder: not porous
  EXPECT_EQ(p.runs[1].cohesion, 1e8);
}
