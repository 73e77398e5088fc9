// The study file: axes expanded in order, explicit runs, run names, and every class of bad study rejected
// with a message naming the key, the value and what is allowed (docs/sweep.md, "Study file").
#include <gtest/gtest.h>

#include <ostream>

#include "craterkit/study/run_name.hpp"
#include "craterkit/study/study_file.hpp"
#include "study_test_helpers.hpp"

using namespace craterkit::study;
using namespace craterkit::study::test;

namespace {

Study parse(const Scratch& scratch, const std::string& text) {
  scratch.write("base.toml", tiny_base());
  const auto file = scratch.write("study.toml", text);
  return load_study(file);
}

std::vector<std::string> names(const Study& study) {
  std::vector<std::string> out;
  for (const auto& run : expand_runs(study)) out.push_back(run_name(run.values));
  return out;
}

}  // namespace

TEST(StudyFile, GridIsTheCartesianProductWithTheLastAxisFastest) {
  Scratch scratch;
  const Study study = parse(scratch, R"([study]
name = "cohesion-size"
base = "base.toml"
[grid]
projectile_mass = [0.05, 2.0, 100]
cohesion = [0.0, 0.05, 0.5]
)");
  EXPECT_EQ(study.name, "cohesion-size");
  EXPECT_EQ(study.law, "jutzi2022_ryugu");
  EXPECT_EQ(study.base, scratch.path() / "base.toml");
  EXPECT_TRUE(study.sizing.enabled);
  EXPECT_DOUBLE_EQ(study.sizing.domain_over_radius, 15.0 / 8.91);
  EXPECT_DOUBLE_EQ(study.sizing.spacings_across_radius, 8.91 / 0.5);
  ASSERT_EQ(study.grid.size(), 2u);
  EXPECT_EQ(study.grid[0].key, "projectile_mass");
  EXPECT_EQ(study.grid[0].kind, AxisKind::projectile_mass);
  const std::vector<std::string> expected = {
      "projectile_mass-0.05_cohesion-0",   "projectile_mass-0.05_cohesion-0.05",
      "projectile_mass-0.05_cohesion-0.5", "projectile_mass-2_cohesion-0",
      "projectile_mass-2_cohesion-0.05",   "projectile_mass-2_cohesion-0.5",
      "projectile_mass-100_cohesion-0",    "projectile_mass-100_cohesion-0.05",
      "projectile_mass-100_cohesion-0.5"};
  EXPECT_EQ(names(study), expected);
  const auto runs = expand_runs(study);
  EXPECT_EQ(runs[5].values[0].number, 2.0);
  EXPECT_EQ(runs[5].values[1].number, 0.5);
  EXPECT_EQ(runs[5].origin, "grid");
}

TEST(StudyFile, ExplicitRunsFollowTheGridAndMayStandAlone) {
  Scratch scratch;
  const Study with_grid = parse(scratch, R"([study]
base = "base.toml"
[grid]
cohesion = [0.0, 1.0]
[[runs]]
cohesion = 0.1
friction = 0.4
[[runs]]
angle_of_repose = 30
"impact.grading" = 0.2
)");
  EXPECT_EQ(with_grid.name, "study");  // the file's stem
  EXPECT_EQ(names(with_grid),
            (std::vector<std::string>{"cohesion-0", "cohesion-1", "cohesion-0.1_friction-0.4",
                                      "angle_of_repose-30_impact.grading-0.2"}));
  const auto runs = expand_runs(with_grid);
  EXPECT_EQ(runs[2].origin, "runs[0]");
  EXPECT_EQ(runs[3].values[1].kind, AxisKind::config_key);
  EXPECT_EQ(runs[3].values[1].literal, "0.2");

  const Study alone = parse(scratch, R"([study]
base = "base.toml"
[[runs]]
cohesion = 2
[[runs]]
)");
  EXPECT_EQ(names(alone), (std::vector<std::string>{"cohesion-2", "base"}));
  EXPECT_EQ(expand_runs(alone)[0].values[0].literal, "2.0");  // a named axis is a float in the configuration
}

TEST(StudyFile, DottedKeysQuotedOrNotAreOneAxisAndKeepTheirType) {
  Scratch scratch;
  const Study study = parse(scratch, R"([study]
base = "base.toml"
[grid]
impact.symmetry = ["full", "quarter"]
"output.checkpoint_interval_steps" = [10]
"target.strength.limiting_strength" = [1e6]
"run.gravity" = [[0.0, 0.0, -2.0]]
)");
  ASSERT_EQ(study.grid.size(), 4u);
  EXPECT_EQ(study.grid[0].key, "impact.symmetry");
  EXPECT_EQ(study.grid[0].values[1].literal, "\"quarter\"");
  EXPECT_EQ(study.grid[1].values[0].literal, "10");  // an integer stays an integer
  EXPECT_EQ(study.grid[2].kind, AxisKind::material_key);
  EXPECT_EQ(study.grid[3].values[0].literal, "[0.0, 0.0, -2.0]");
  EXPECT_EQ(value_slug(study.grid[3].values[0]), "0.0,0.0,-2.0");
  EXPECT_EQ(run_name({study.grid[0].values[1], study.grid[2].values[0]}),
            "impact.symmetry-quarter_target.strength.limiting_strength-1e+06");
}

TEST(StudyFile, RunNamesAreFilesystemSafeAndBounded) {
  AxisValue text{"impact.projectile_material", AxisKind::config_key, "\"my dir/al.toml\"", std::nullopt};
  EXPECT_EQ(run_name({text}), "impact.projectile_material-my_dir_al.toml");
  AxisValue tiny{"cohesion", AxisKind::cohesion, "1e-05", 1e-5};
  EXPECT_EQ(run_name({tiny}), "cohesion-1e-05");
  std::vector<AxisValue> many;
  for (int i = 0; i < 20; ++i) many.push_back({"impact.grading", AxisKind::config_key, "0.1", 0.1 + i});
  const std::string name = run_name(many);
  EXPECT_EQ(name.size(), 120u);
  EXPECT_NE(name, run_name(std::vector<AxisValue>(many.begin(), many.end() - 1)));
}

TEST(StudyFile, SizingTableAndLaw) {
  Scratch scratch;
  const Study study = parse(scratch, R"([study]
base = "base.toml"
law = "holsapple1993_dry_sand"
[sizing]
enabled = false
domain_over_radius = 2
spacings_across_radius = 10
core_spacing_over_projectile_radius = 0.25
end_time_over_growth_time = 3
[[runs]]
)");
  EXPECT_EQ(study.law, "holsapple1993_dry_sand");
  EXPECT_FALSE(study.sizing.enabled);
  EXPECT_EQ(study.sizing.domain_over_radius, 2.0);
  EXPECT_EQ(study.sizing.spacings_across_radius, 10.0);
  EXPECT_EQ(study.sizing.core_spacing_over_projectile_radius, 0.25);
  EXPECT_EQ(study.sizing.end_time_over_growth_time, 3.0);
}

TEST(StudyFile, ABaseNameIsAShippedExample) {
  Scratch scratch;
  for (const std::string base : {"sci.toml", "sci"}) {
    const Study study = parse(scratch, "[study]\nbase = \"" + base + "\"\n[[runs]]\n");
    EXPECT_EQ(study.base.filename(), "sci.toml");
    EXPECT_EQ(study.base.parent_path().filename(), "examples");
  }
}

struct BadStudy {
  std::string what;
  std::string text;
  std::vector<std::string> expected;  // each must appear in the message
};

// GoogleTest names each case by what it tests instead of printing the struct's bytes.
void PrintTo(const BadStudy& bad, std::ostream* out) {
  *out << bad.what;
}

class StudyFileRejects : public ::testing::TestWithParam<BadStudy> {};

TEST_P(StudyFileRejects, NamingTheKey) {
  Scratch scratch;
  const auto& bad = GetParam();
  const std::string message = input_error([&] { parse(scratch, bad.text); });
  for (const auto& part : bad.expected)
    EXPECT_NE(message.find(part), std::string::npos) << bad.what << ": " << message;
  EXPECT_NE(message.find("study.toml"), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    All, StudyFileRejects,
    ::testing::Values(
        BadStudy{
            "unknown key in [study]", "[study]\nbase = \"base.toml\"\nbsae = 1\n[[runs]]\n", {"study.bsae"}},
        BadStudy{"unknown table", "[study]\nbase = \"base.toml\"\n[grdi]\ncohesion = [1]\n", {"grdi"}},
        BadStudy{"unknown sizing key",
                 "[study]\nbase = \"base.toml\"\n[sizing]\nfactor = 2\n[[runs]]\n",
                 {"sizing.factor"}},
        BadStudy{"unknown axis",
                 "[study]\nbase = \"base.toml\"\n[grid]\ncohesoin = [1.0]\n",
                 {"grid.cohesoin", "allowed", "cohesion"}},
        BadStudy{"empty axis",
                 "[study]\nbase = \"base.toml\"\n[grid]\ncohesion = []\n",
                 {"grid.cohesion", "non-empty array"}},
        BadStudy{"scalar grid axis",
                 "[study]\nbase = \"base.toml\"\n[grid]\ncohesion = 1.0\n",
                 {"grid.cohesion", "non-empty array"}},
        BadStudy{"negative mass",
                 "[study]\nbase = \"base.toml\"\n[grid]\nprojectile_mass = [1.0, -2.0]\n",
                 {"grid.projectile_mass", "-2", "> 0"}},
        BadStudy{"zero mass",
                 "[study]\nbase = \"base.toml\"\n[[runs]]\nprojectile_mass = 0\n",
                 {"runs[0].projectile_mass", "> 0"}},
        BadStudy{"negative cohesion",
                 "[study]\nbase = \"base.toml\"\n[[runs]]\n[[runs]]\ncohesion = -1\n",
                 {"runs[1].cohesion", "-1", ">= 0"}},
        BadStudy{"negative friction",
                 "[study]\nbase = \"base.toml\"\n[grid]\nfriction = [-0.1]\n",
                 {"grid.friction", "-0.1"}},
        BadStudy{"porosity 1",
                 "[study]\nbase = \"base.toml\"\n[grid]\nporosity = [0.5, 1.0]\n",
                 {"grid.porosity", "(0, 1)"}},
        BadStudy{"angle of repose 90",
                 "[study]\nbase = \"base.toml\"\n[grid]\nangle_of_repose = [90]\n",
                 {"grid.angle_of_repose", "90"}},
        BadStudy{"text for a named axis",
                 "[study]\nbase = \"base.toml\"\n[grid]\ncohesion = [\"soft\"]\n",
                 {"grid.cohesion", "expected a number"}},
        BadStudy{
            "mass and radius",
            "[study]\nbase = \"base.toml\"\n[grid]\nprojectile_mass = [1.0]\nprojectile_radius = [0.1]\n",
            {"grid.projectile_radius", "projectile_mass", "one of them"}},
        BadStudy{"mass and radius in one run",
                 "[study]\nbase = \"base.toml\"\n[[runs]]\nprojectile_radius = 0.1\nprojectile_mass = 1.0\n",
                 {"runs[0]", "projectile_radius"}},
        BadStudy{"friction and angle",
                 "[study]\nbase = \"base.toml\"\n[[runs]]\nfriction = 0.5\nangle_of_repose = 30\n",
                 {"runs[0].angle_of_repose", "friction"}},
        BadStudy{"a value twice in an axis",
                 "[study]\nbase = \"base.toml\"\n[grid]\ncohesion = [1, 1.0]\n",
                 {"grid.cohesion", "twice"}},
        BadStudy{"a key the sizing rule sets",
                 "[study]\nbase = \"base.toml\"\n[grid]\n\"impact.domain_radius\" = [5.0]\n",
                 {"grid.impact.domain_radius", "sizing"}},
        BadStudy{"a key an axis sets",
                 "[study]\nbase = \"base.toml\"\n[grid]\n\"impact.projectile_mass\" = [5.0]\n",
                 {"grid.impact.projectile_mass", "projectile_mass"}},
        BadStudy{"resolution without sizing",
                 "[study]\nbase = \"base.toml\"\n[sizing]\nenabled = false\n[grid]\nresolution = [10]\n",
                 {"grid.resolution", "sizing"}},
        BadStudy{"no runs", "[study]\nbase = \"base.toml\"\n", {"no runs"}},
        BadStudy{"runs not tables", "[study]\nbase = \"base.toml\"\nruns = [1, 2]\n", {"runs"}},
        BadStudy{"missing base", "[study]\nname = \"x\"\n[[runs]]\n", {"study.base"}},
        BadStudy{
            "base not found", "[study]\nbase = \"nothere.toml\"\n[[runs]]\n", {"study.base", "nothere.toml"}},
        BadStudy{"bad sizing factor",
                 "[study]\nbase = \"base.toml\"\n[sizing]\ndomain_over_radius = -1\n[[runs]]\n",
                 {"sizing.domain_over_radius"}}),
    [](const ::testing::TestParamInfo<BadStudy>& param) {
      std::string name;
      for (const char c : param.param.what) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
      return name;
    });
