// Loading materials from data/materials/*.toml: the shipped values equal docs/physics.md's table, and bad
// files fail with an InputError naming the file and the key.
#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "craterkit/common/input_error.hpp"
#include "craterkit/sph/io/material_file.hpp"
#include "craterkit/sph/physics/material.hpp"
#include "craterkit/sph/physics/material_response.hpp"

namespace {

using craterkit::InputError;
using craterkit::sph::evaluate_material;
using craterkit::sph::IdealGas;
using craterkit::sph::load_material;
using craterkit::sph::LowSoundSpeed;
using craterkit::sph::LundborgStrength;
using craterkit::sph::Material;
using craterkit::sph::material_names;
using craterkit::sph::Tillotson;
using craterkit::sph::VonMisesStrength;
using craterkit::sph::WeakeningStrain;

TEST(Material, BasaltMatchesPhysicsTable) {
  const auto m = load_material("basalt");
  EXPECT_EQ(m.name, "basalt");
  EXPECT_NE(m.citation.find("Benz & Asphaug (1999)"), std::string::npos);
  ASSERT_TRUE(std::holds_alternative<Tillotson>(m.eos));
  const auto& t = std::get<Tillotson>(m.eos);
  EXPECT_EQ(t.reference_density, 2700.0);
  EXPECT_EQ(t.A, 26.7e9);
  EXPECT_EQ(t.B, 26.7e9);
  EXPECT_EQ(t.E0, 487e6);
  EXPECT_EQ(t.E_iv, 4.72e6);
  EXPECT_EQ(t.E_cv, 18.2e6);
  EXPECT_EQ(t.a, 0.5);
  EXPECT_EQ(t.b, 1.5);
  EXPECT_EQ(t.alpha, 5.0);
  EXPECT_EQ(t.beta, 5.0);
  EXPECT_EQ(t.min_sound_speed_fraction, 0.01);
  EXPECT_EQ(m.shear_modulus, 22.7e9);
}

TEST(Material, AluminiumMatchesPhysicsTable) {
  const auto m = load_material("aluminium");
  EXPECT_NE(m.citation.find("Tillotson (1962)"), std::string::npos);
  const auto& t = std::get<Tillotson>(m.eos);
  EXPECT_EQ(t.reference_density, 2700.0);
  EXPECT_EQ(t.A, 75.2e9);
  EXPECT_EQ(t.B, 65.0e9);
  EXPECT_EQ(t.E0, 5.0e6);
  EXPECT_EQ(t.E_iv, 3.0e6);
  EXPECT_EQ(t.E_cv, 13.9e6);
  EXPECT_EQ(t.a, 0.5);
  EXPECT_EQ(t.b, 1.63);
  EXPECT_EQ(t.alpha, 5.0);
  EXPECT_EQ(t.beta, 5.0);
  EXPECT_EQ(m.shear_modulus, 26.7e9);
}

TEST(Material, RyuguMatrixIsBasaltWithSolidDensity2600) {
  const auto basalt = std::get<Tillotson>(load_material("basalt").eos);
  const auto m = load_material("basalt_matrix_ryugu");
  const auto& t = std::get<Tillotson>(m.eos);
  EXPECT_EQ(t.reference_density, 2600.0);
  EXPECT_EQ(t.A, basalt.A);
  EXPECT_EQ(t.B, basalt.B);
  EXPECT_EQ(t.E0, basalt.E0);
  EXPECT_EQ(t.E_iv, basalt.E_iv);
  EXPECT_EQ(t.E_cv, basalt.E_cv);
  EXPECT_EQ(t.a, basalt.a);
  EXPECT_EQ(t.b, basalt.b);
  EXPECT_EQ(t.alpha, basalt.alpha);
  EXPECT_EQ(t.beta, basalt.beta);
  EXPECT_EQ(m.shear_modulus, 22.7e9);
}

// The Ryugu target of docs/physics.md: cohesionless Lundborg with the SCI friction, nominal P-alpha.
TEST(Material, RyuguTargetStrengthAndPorosity) {
  const auto m = load_material("basalt_matrix_ryugu");
  ASSERT_TRUE(m.strength.has_value());
  ASSERT_TRUE(std::holds_alternative<LundborgStrength>(*m.strength));
  const auto& s = std::get<LundborgStrength>(*m.strength);
  EXPECT_EQ(s.cohesion, 0.0);
  EXPECT_EQ(s.friction_coefficient, 0.55);
  EXPECT_EQ(s.limiting_strength, 3.5e9);
  ASSERT_TRUE(m.porosity.has_value());
  const auto& p = m.porosity->crush_curve;
  EXPECT_EQ(p.initial_distention, 2.0);
  EXPECT_EQ(p.transition_distention, 1.25);
  EXPECT_EQ(p.elastic_pressure, 1.0e6);
  EXPECT_EQ(p.transition_pressure, 68.0e6);
  EXPECT_EQ(p.solid_pressure, 213.0e6);
  EXPECT_EQ(p.exponent_1, 12.0);
  EXPECT_EQ(p.exponent_2, 3.0);
  EXPECT_EQ(m.porosity->porous_sound_speed, 1500.0);
  // Derived by the loader: sqrt(26.7e9 / 2600) = 3204.564052914338 m/s.
  EXPECT_NEAR(m.porosity->matrix_sound_speed, 3204.564052914338, 1e-9);
  // Nominal bulk density 2600 / 2 = 1300 kg/m^3 (docs/physics.md).
  EXPECT_EQ(std::get<Tillotson>(m.eos).reference_density / p.initial_distention, 1300.0);
}

TEST(Material, BoulderIsBasaltAtTheBulkDensityWithCohesion) {
  const auto basalt = std::get<Tillotson>(load_material("basalt").eos);
  const auto m = load_material("boulder");
  const auto& t = std::get<Tillotson>(m.eos);
  EXPECT_EQ(t.reference_density, 1300.0);
  EXPECT_EQ(t.A, basalt.A);
  EXPECT_EQ(t.B, basalt.B);
  EXPECT_EQ(t.E0, basalt.E0);
  EXPECT_EQ(t.b, basalt.b);
  EXPECT_FALSE(m.porosity.has_value());
  const auto& s = std::get<LundborgStrength>(m.strength.value());
  EXPECT_EQ(s.cohesion, 1.0e8);
  EXPECT_EQ(s.friction_coefficient, 0.8);
  EXPECT_EQ(s.limiting_strength, 3.5e9);
  // Chosen by the boulder runs at the SCI site (docs/validation.md, "Boulders at the example's resolution").
  EXPECT_EQ(s.weakening_strain, WeakeningStrain::plastic_after_switch);
}

TEST(Material, ProjectileIsAluminiumWithVonMises) {
  const auto plate = load_material("aluminium");
  EXPECT_FALSE(plate.strength.has_value());  // the hydrodynamic validation plate stays strengthless
  const auto m = load_material("aluminium_projectile");
  const auto& t = std::get<Tillotson>(m.eos);
  const auto& al = std::get<Tillotson>(plate.eos);
  EXPECT_EQ(t.reference_density, 2700.0);  // docs/physics.md's SCI stand-in density
  EXPECT_EQ(t.A, al.A);
  EXPECT_EQ(t.B, al.B);
  EXPECT_EQ(t.E0, al.E0);
  EXPECT_EQ(t.E_iv, al.E_iv);
  EXPECT_EQ(t.E_cv, al.E_cv);
  EXPECT_EQ(t.b, al.b);
  EXPECT_EQ(m.shear_modulus, plate.shear_modulus);
  EXPECT_EQ(std::get<VonMisesStrength>(m.strength.value()).yield_strength, 0.34e9);
  EXPECT_FALSE(m.porosity.has_value());
}

TEST(Material, IdealGases) {
  const auto diatomic = load_material("ideal_gas_diatomic");
  EXPECT_EQ(std::get<IdealGas>(diatomic.eos).gamma, 1.4);
  EXPECT_EQ(diatomic.shear_modulus, 0.0);
  EXPECT_DOUBLE_EQ(std::get<IdealGas>(load_material("ideal_gas_monatomic").eos).gamma, 5.0 / 3.0);
}

TEST(Material, NamesListsEveryShippedFileAndEachLoads) {
  const auto names = material_names();
  for (const char* expected : {"aluminium", "aluminium_projectile", "basalt", "basalt_matrix_ryugu",
                               "boulder", "ideal_gas_diatomic", "ideal_gas_monatomic"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  }
  EXPECT_TRUE(std::is_sorted(names.begin(), names.end()));
  for (const auto& name : names) {
    const auto m = load_material(name);
    EXPECT_EQ(m.name, name);
    EXPECT_FALSE(m.citation.empty()) << name;
  }
}

TEST(Material, UnknownNameListsTheShippedOnes) {
  try {
    load_material("granite");
    FAIL() << "no error for an unknown material";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("granite"), std::string::npos) << message;
    EXPECT_NE(message.find("basalt"), std::string::npos) << message;
  }
}

// Writes `text` to a fresh file and loads it; returns the error message (empty if it loaded).
class BadMaterialFile : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ =
        std::filesystem::temp_directory_path() / ("craterkit_material_test_" + std::to_string(::getpid()));
    std::filesystem::create_directories(directory_);
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }

  std::string error_of(const std::string& text) {
    const auto path = directory_ / "rock.toml";
    std::ofstream(path) << text;
    try {
      load_material(path.string());
    } catch (const InputError& e) {
      return e.what();
    }
    return {};
  }

  static std::string valid_tillotson() {
    return "citation = \"test\"\nshear_modulus = 1e9\n[eos]\nmodel = \"tillotson\"\nreference_density = "
           "2700\n"
           "A = 26.7e9\nB = 26.7e9\nE0 = 487e6\nE_iv = 4.72e6\nE_cv = 18.2e6\na = 0.5\nb = 1.5\nalpha = 5\n"
           "beta = 5\n";
  }

  static std::string replace(std::string text, const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  }

  std::filesystem::path directory_;
};

void expect_mentions(const std::string& message, std::initializer_list<const char*> parts) {
  EXPECT_FALSE(message.empty()) << "no error";
  for (const char* part : parts) EXPECT_NE(message.find(part), std::string::npos) << message << " / " << part;
}

TEST_F(BadMaterialFile, ValidFileLoadsByPathWithDefaults) {
  EXPECT_EQ(error_of(valid_tillotson()), "");
  const auto m = load_material((directory_ / "rock.toml").string());
  EXPECT_EQ(m.name, "rock");
  EXPECT_EQ(std::get<Tillotson>(m.eos).min_sound_speed_fraction, 0.01);  // default
  EXPECT_EQ(std::get<Tillotson>(m.eos).alpha, 5.0);                      // integer accepted as a number
}

TEST_F(BadMaterialFile, UnknownKeysAreNamed) {
  expect_mentions(error_of(valid_tillotson() + "gamma = 1.4\n"), {"rock.toml", "eos.gamma", "unknown"});
  expect_mentions(error_of("colour = \"grey\"\n" + valid_tillotson()), {"unknown key colour"});
  expect_mentions(
      error_of(valid_tillotson() + "[strength]\nmodel = \"von_mises\"\nyield_strength = 1e8\nY = 2\n"),
      {"unknown key strength.Y"});
  expect_mentions(error_of(valid_tillotson() + "[damage]\nweibull_k = 1\n"), {"unknown key damage"});
}

TEST_F(BadMaterialFile, OutOfRangeValuesAreNamedWithTheValue) {
  expect_mentions(error_of(replace(valid_tillotson(), "A = 26.7e9", "A = -5")), {"eos.A", "-5", "(0, inf)"});
  expect_mentions(error_of(replace(valid_tillotson(), "E_cv = 18.2e6", "E_cv = 1e6")),
                  {"eos.E_cv", "> E_iv"});
  expect_mentions(error_of(replace(valid_tillotson(), "shear_modulus = 1e9", "shear_modulus = -1")),
                  {"shear_modulus", "-1"});
  expect_mentions(error_of(valid_tillotson() + "min_sound_speed_fraction = 2\n"),
                  {"eos.min_sound_speed_fraction", "(0, 1]"});
  expect_mentions(error_of("citation = \"x\"\n[eos]\nmodel = \"ideal_gas\"\ngamma = 0.9\n"),
                  {"eos.gamma", "(1, inf)"});
  expect_mentions(
      error_of("citation = \"x\"\nshear_modulus = 3.0\n[eos]\nmodel = \"ideal_gas\"\ngamma = 1.4\n"),
      {"shear_modulus", "ideal gas"});
}

TEST_F(BadMaterialFile, MissingAndMistypedKeysAreNamed) {
  expect_mentions(error_of(replace(valid_tillotson(), "E0 = 487e6\n", "")), {"eos.E0", "missing"});
  expect_mentions(error_of(replace(valid_tillotson(), "shear_modulus = 1e9\n", "")),
                  {"shear_modulus", "missing"});
  expect_mentions(error_of(replace(valid_tillotson(), "citation = \"test\"\n", "")), {"citation", "missing"});
  expect_mentions(error_of("citation = \"x\"\n"), {"eos", "missing"});
  expect_mentions(error_of(replace(valid_tillotson(), "B = 26.7e9", "B = \"big\"")), {"eos.B", "number"});
  expect_mentions(error_of(replace(valid_tillotson(), "model = \"tillotson\"", "model = \"aneos\"")),
                  {"eos.model", "\"tillotson\", \"low_sound_speed\", \"ideal_gas\""});
}

TEST_F(BadMaterialFile, SyntaxErrorsAndMissingFiles) {
  expect_mentions(error_of("citation = \n"), {"rock.toml:1", "TOML syntax error"});
  try {
    load_material((directory_ / "absent.toml").string());
    FAIL() << "no error for a missing file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("absent.toml"), std::string::npos);
  }
}

std::string lundborg(const std::string& friction_lines) {
  return "[strength]\nmodel = \"lundborg\"\ncohesion = 1e5\n" + friction_lines;
}

std::string nominal_porosity() {
  return "[porosity]\nmodel = \"p_alpha\"\ninitial_distention = 2\ntransition_distention = 1.25\n"
         "elastic_pressure = 1e6\ntransition_pressure = 68e6\nsolid_pressure = 213e6\nexponent_1 = 12\n"
         "exponent_2 = 3\nporous_sound_speed = 1500\n";
}

TEST_F(BadMaterialFile, StrengthAndPorosityBlocksLoad) {
  ASSERT_EQ(error_of(valid_tillotson() + lundborg("friction_coefficient = 0.6\n") + nominal_porosity()), "");
  const auto m = load_material((directory_ / "rock.toml").string());
  const auto& s = std::get<LundborgStrength>(m.strength.value());
  EXPECT_EQ(s.cohesion, 1e5);
  EXPECT_EQ(s.friction_coefficient, 0.6);
  EXPECT_EQ(s.limiting_strength, 3.5e9);  // default Y_dm of docs/physics.md
  EXPECT_EQ(m.porosity->crush_curve.exponent_1, 12.0);
  EXPECT_EQ(m.porosity->porous_sound_speed, 1500.0);
  EXPECT_NEAR(m.porosity->matrix_sound_speed, 3144.660377352201, 1e-9);  // sqrt(26.7e9/2700)

  EXPECT_EQ(s.weakening_strain, WeakeningStrain::total);  // the published model
  for (const auto& [text, value] : {std::pair{"total", WeakeningStrain::total},
                                    std::pair{"plastic_after_switch", WeakeningStrain::plastic_after_switch},
                                    std::pair{"plastic", WeakeningStrain::plastic}}) {
    ASSERT_EQ(error_of(valid_tillotson() + lundborg("friction_coefficient = 0.6\nweakening_strain = \"" +
                                                    std::string(text) + "\"\n")),
              "");
    EXPECT_EQ(std::get<LundborgStrength>(load_material((directory_ / "rock.toml").string()).strength.value())
                  .weakening_strain,
              value)
        << text;
  }

  ASSERT_EQ(error_of(valid_tillotson() + "[strength]\nmodel = \"von_mises\"\nyield_strength = 2e8\n"), "");
  EXPECT_EQ(std::get<VonMisesStrength>(load_material((directory_ / "rock.toml").string()).strength.value())
                .yield_strength,
            2e8);
}

// f = 2 sqrt(2) sin(theta) / (3 - sin(theta)) (Luther et al. 2022), by hand:
// 30 deg: sin = 1/2, f = sqrt(2)/2.5 = 0.565685424949238; 22 deg: sin = 0.374606593415912,
// f = 2.82842712474619 * 0.374606593415912 / 2.625393406584088 = 0.403576640083406; 45 deg: sin = sqrt(2)/2,
// f = 2 / (3 - 0.707106781186548) = 0.872260419102717.
TEST_F(BadMaterialFile, ReposeAngleGivesTheFrictionCoefficient) {
  const std::pair<double, double> cases[] = {{30.0, 0.565685424949238},
                                             {22.0, 2.82842712474619 * 0.374606593415912 / 2.625393406584088},
                                             {45.0, 0.872260419102717}};
  for (const auto& [angle, expected] : cases) {
    ASSERT_EQ(
        error_of(valid_tillotson() + lundborg("repose_angle_degrees = " + std::to_string(angle) + "\n")), "");
    const auto m = load_material((directory_ / "rock.toml").string());
    EXPECT_NEAR(std::get<LundborgStrength>(m.strength.value()).friction_coefficient, expected, 1e-13)
        << angle;
  }
}

TEST_F(BadMaterialFile, MalformedStrengthIsNamed) {
  const std::string base = valid_tillotson();
  expect_mentions(error_of(base + lundborg("friction_coefficient = 0.5\nrepose_angle_degrees = 30\n")),
                  {"strength.repose_angle_degrees", "strength.friction_coefficient", "exactly one"});
  expect_mentions(error_of(base + lundborg("")),
                  {"strength.friction_coefficient", "missing", "repose_angle_degrees"});
  expect_mentions(error_of(base + lundborg("friction_coefficient = 0.5\nweakening_strain = \"elastic\"\n")),
                  {"strength.weakening_strain", "elastic", "plastic_after_switch"});
  expect_mentions(error_of(base + lundborg("repose_angle_degrees = 95\n")),
                  {"strength.repose_angle_degrees", "95", "(0, 90)"});
  expect_mentions(error_of(base + lundborg("friction_coefficient = -0.1\n")),
                  {"strength.friction_coefficient", "-0.1", "[0, inf)"});
  expect_mentions(error_of(base + lundborg("friction_coefficient = 0.5\nlimiting_strength = 1e4\n")),
                  {"strength.limiting_strength", "10000", "> cohesion"});
  expect_mentions(
      error_of(base + "[strength]\nmodel = \"lundborg\"\ncohesion = 4e9\nfriction_coefficient = 1\n"),
      {"strength.cohesion", "limiting_strength"});
  expect_mentions(
      error_of(base + "[strength]\nmodel = \"lundborg\"\ncohesion = -1\nfriction_coefficient = 1\n"),
      {"strength.cohesion", "-1", "[0, inf)"});
  expect_mentions(error_of(base + "[strength]\nmodel = \"lundborg\"\nfriction_coefficient = 1\n"),
                  {"strength.cohesion", "missing"});
  expect_mentions(error_of(base + lundborg("friction_coefficient = 0.5\nangle = 3\n")),
                  {"strength.angle", "unknown"});
  expect_mentions(error_of(base + "[strength]\nmodel = \"mohr_coulomb\"\n"),
                  {"strength.model", "mohr_coulomb", "\"lundborg\", \"von_mises\""});
  expect_mentions(error_of(base + "[strength]\ncohesion = 1\n"), {"strength.model", "missing"});
  expect_mentions(error_of(base + "[strength]\nmodel = \"von_mises\"\n"),
                  {"strength.yield_strength", "missing"});
  expect_mentions(error_of(base + "[strength]\nmodel = \"von_mises\"\nyield_strength = 0\n"),
                  {"strength.yield_strength", "(0, inf)"});
  expect_mentions(error_of(base + "[strength]\nmodel = \"von_mises\"\nyield_strength = 1e8\ncohesion = 1\n"),
                  {"strength.cohesion", "unknown"});
  expect_mentions(error_of(replace(base, "shear_modulus = 1e9", "shear_modulus = 0") +
                           "[strength]\nmodel = \"von_mises\"\nyield_strength = 1e8\n"),
                  {"shear_modulus", "> 0"});
  expect_mentions(error_of("citation = \"x\"\n[eos]\nmodel = \"ideal_gas\"\ngamma = 1.4\n[strength]\n"
                           "model = \"von_mises\"\nyield_strength = 1e8\n"),
                  {"rock.toml: strength: ", "ideal gas"});
  expect_mentions(error_of("strength = 3\n" + base), {"rock.toml: strength: ", "table"});
}

TEST_F(BadMaterialFile, MalformedPorosityIsNamed) {
  const std::string base = valid_tillotson();
  const std::string nominal = nominal_porosity();
  const auto with = [&](const std::string& from, const std::string& to) {
    return error_of(base + replace(nominal, from, to));
  };
  expect_mentions(with("initial_distention = 2", "initial_distention = 1.1"),
                  {"porosity.initial_distention", "1.1", ">= transition_distention"});
  expect_mentions(with("transition_distention = 1.25", "transition_distention = 0.9"),
                  {"porosity.transition_distention", "0.9", "[1, inf)"});
  expect_mentions(with("elastic_pressure = 1e6", "elastic_pressure = -1"),
                  {"porosity.elastic_pressure", "[0, inf)"});
  expect_mentions(with("transition_pressure = 68e6", "transition_pressure = 1e6"),
                  {"porosity.transition_pressure", "> elastic_pressure"});
  expect_mentions(with("solid_pressure = 213e6", "solid_pressure = 68e6"),
                  {"porosity.solid_pressure", "> transition_pressure"});
  expect_mentions(with("exponent_1 = 12", "exponent_1 = 0"), {"porosity.exponent_1", "(0, inf)"});
  expect_mentions(with("exponent_2 = 3", "exponent_2 = -3"), {"porosity.exponent_2", "-3", "(0, inf)"});
  expect_mentions(with("porous_sound_speed = 1500", "porous_sound_speed = 4000"),
                  {"porosity.porous_sound_speed", "4000", "3144.66"});
  expect_mentions(with("porous_sound_speed = 1500", "porous_sound_speed = 0"),
                  {"porosity.porous_sound_speed", "(0, 3144.66"});
  expect_mentions(with("porous_sound_speed = 1500\n", ""), {"porosity.porous_sound_speed", "missing"});
  expect_mentions(with("exponent_2 = 3\n", ""), {"porosity.exponent_2", "missing"});
  expect_mentions(with("model = \"p_alpha\"", "model = \"epsilon_alpha\""),
                  {"porosity.model", "epsilon_alpha", "p_alpha"});
  expect_mentions(error_of(base + nominal + "crush_exponent = 1\n"), {"porosity.crush_exponent", "unknown"});
  expect_mentions(error_of("citation = \"x\"\n[eos]\nmodel = \"ideal_gas\"\ngamma = 1.4\n" + nominal),
                  {"rock.toml: porosity: ", "ideal gas"});
}

TEST_F(BadMaterialFile, LowSoundSpeedLawLoads) {
  ASSERT_EQ(error_of("citation = \"x\"\nshear_modulus = 2e4\n[eos]\nmodel = \"low_sound_speed\"\n"
                     "reference_density = 2600\nA = 2.7e4\n"),
            "");
  const auto m = load_material((directory_ / "rock.toml").string());
  const auto& law = std::get<LowSoundSpeed>(m.eos);
  EXPECT_EQ(law.reference_density, 2600.0);
  EXPECT_EQ(law.A, 2.7e4);
  expect_mentions(error_of("citation = \"x\"\nshear_modulus = 2e4\n[eos]\nmodel = \"low_sound_speed\"\n"
                           "reference_density = 2600\nA = 0\n"),
                  {"eos.A", "(0, inf)"});
  expect_mentions(error_of("citation = \"x\"\nshear_modulus = 2e4\n[eos]\nmodel = \"low_sound_speed\"\n"
                           "reference_density = 2600\nA = 1\nB = 1\n"),
                  {"eos.B", "unknown"});
}

}  // namespace

// The 30 % and 60 % porous targets are the 50 % target's material at another initial compaction: the same
// matrix, strength and crush curve; alpha0 = 1/(1 - phi), so the bulk density at rest is 2600 (1 - phi); and
// their unloaded sound speed is the one the 50 % target's P-alpha response gives at that distention (its
// h(alpha) line from c_s at alpha = 1 to 1500 m/s at alpha = 2), so the three share one sound-speed law.
TEST(Material, PorosityVariantsLieOnTheNominalTargetsLine) {
  const Material nominal = load_material("basalt_matrix_ryugu");
  for (const auto& [name, phi] :
       {std::pair{"basalt_matrix_ryugu_30", 0.3}, std::pair{"basalt_matrix_ryugu_60", 0.6}}) {
    const Material m = load_material(name);
    ASSERT_TRUE(m.porosity.has_value()) << name;
    const double alpha0 = m.porosity->crush_curve.initial_distention;
    EXPECT_NEAR(alpha0, 1.0 / (1.0 - phi), 1e-12) << name;
    EXPECT_NEAR(2600.0 / alpha0, 2600.0 * (1.0 - phi), 1e-9) << name;
    EXPECT_EQ(m.shear_modulus, nominal.shear_modulus) << name;
    EXPECT_EQ(m.porosity->crush_curve.transition_distention,
              nominal.porosity->crush_curve.transition_distention);
    EXPECT_EQ(m.porosity->crush_curve.solid_pressure, nominal.porosity->crush_curve.solid_pressure);
    // Cold and unloaded at alpha0: the variant's own c_e is on the line c_s + (alpha - 1)(1500 m/s - c_s).
    const double c_s = std::sqrt(26.7e9 / 2600.0);
    const double own = evaluate_material(m, 2600.0 / alpha0, 0.0, alpha0, 0.0).sound_speed;
    EXPECT_NEAR(own, c_s + (alpha0 - 1.0) * (1500.0 - c_s), 0.06) << name;  // c_e is written to 0.1 m/s
    // Within the nominal target's range of distention (30 %), that is its own P-alpha response there.
    if (alpha0 < 2.0) {
      EXPECT_NEAR(own, evaluate_material(nominal, 2600.0 / alpha0, 0.0, alpha0, 0.0).sound_speed, 0.06)
          << name;
    }
  }
}
