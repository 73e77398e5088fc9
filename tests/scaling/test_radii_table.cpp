// The impacts-and-radii CSV reader: good tables, sweep tables with information and grouping columns, and
// every malformed case (misspelt columns included), each reported with its line and column.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/radii_table.hpp"

namespace cs = craterkit::scaling;

namespace {

const std::string kHeader =
    "impactor_radius,impactor_density,velocity,target_density,gravity,strength,crater_radius\n";
const std::string kRow = "0.05,2700,2000,1300,1.4e-4,0.05,7.2\n";

cs::RadiiTable parse(const std::string& text) {
  std::istringstream in(text);
  return cs::parse_radii_csv(in, "t.csv");
}

// The error message for `text`, or "" if it parses.
std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const craterkit::InputError& e) {
    return e.what();
  }
  return "";
}

void expect_error(const std::string& text, const std::string& must_contain_1,
                  const std::string& must_contain_2) {
  const std::string message = error_of(text);
  ASSERT_FALSE(message.empty()) << "no error for:\n" << text;
  EXPECT_NE(message.find(must_contain_1), std::string::npos) << message;
  EXPECT_NE(message.find(must_contain_2), std::string::npos) << message;
}

}  // namespace

TEST(RadiiTable, ReadsColumnsInAnyOrderWithCommentsAndSigma) {
  const auto table = parse(
      "# a comment\n"
      "crater_radius, strength, gravity, target_density, velocity, impactor_density, impactor_radius, "
      "crater_radius_sigma\n"
      "\n"
      "7.2, 0.05, 1.4e-4, 1300, 2000, 2700, 0.05, 0.8\n"
      "# another\n"
      "3.0, 5, 0, 1300, 2000, 2700, 0.05, 0.3\n");
  ASSERT_EQ(table.rows.size(), 2u);
  EXPECT_TRUE(table.has_sigma());
  const auto& row = table.rows[0];
  EXPECT_EQ(row.line, 4);
  EXPECT_DOUBLE_EQ(row.crater_radius, 7.2);
  EXPECT_DOUBLE_EQ(row.target.strength, 0.05);
  EXPECT_DOUBLE_EQ(row.target.gravity, 1.4e-4);
  EXPECT_DOUBLE_EQ(row.target.density, 1300.0);
  EXPECT_DOUBLE_EQ(row.impactor.velocity, 2000.0);
  EXPECT_DOUBLE_EQ(row.impactor.density, 2700.0);
  EXPECT_DOUBLE_EQ(row.impactor.radius, 0.05);
  EXPECT_DOUBLE_EQ(row.crater_radius_sigma.value(), 0.8);
  EXPECT_DOUBLE_EQ(table.rows[1].target.gravity, 0.0);
  // format -> parse round trip
  const auto again = parse(cs::format_radii_csv(table));
  ASSERT_EQ(again.rows.size(), 2u);
  EXPECT_DOUBLE_EQ(again.rows[1].crater_radius_sigma.value(), 0.3);
  EXPECT_DOUBLE_EQ(again.rows[1].crater_radius, 3.0);
}

TEST(RadiiTable, WithoutSigmaColumnRowsAreUnweighted) {
  const auto table = parse(kHeader + kRow);
  EXPECT_FALSE(table.has_sigma());
  EXPECT_FALSE(table.rows[0].crater_radius_sigma.has_value());
}

TEST(RadiiTable, EveryMalformedCaseNamesItsPlace) {
  expect_error("", "t.csv", "empty file");
  expect_error("# only a comment\n", "t.csv", "empty file");
  expect_error(kHeader, "t.csv", "no data rows");
  // a missing column
  expect_error(
      "impactor_radius,impactor_density,velocity,target_density,gravity,crater_radius\n"
      "0.05,2700,2000,1300,1.4e-4,7.2\n",
      "t.csv:1", "'strength'");
  // a repeated column (an unknown one is a grouping column: see the sweep tables below)
  expect_error("strength," + kHeader, "t.csv:1", "'strength' appears twice");
  // a non-number, NaN, infinity, an empty cell
  expect_error(kHeader + kRow + "0.05,2700,fast,1300,1.4e-4,0.05,7.2\n", "t.csv:3",
               "column 'velocity': 'fast'");
  expect_error(kHeader + "0.05,2700,2000,1300,1.4e-4,0.05,nan\n", "t.csv:2", "column 'crater_radius': 'nan'");
  expect_error(kHeader + "0.05,2700,2000,1300,inf,0.05,7.2\n", "t.csv:2", "column 'gravity': 'inf'");
  expect_error(kHeader + "0.05,2700,2000,1300,,0.05,7.2\n", "t.csv:2", "column 'gravity': empty");
  expect_error(kHeader + "0.05,2700,2000,1300,1.4e-4,0.05,7.2x\n", "t.csv:2", "'7.2x' is not a number");
  // non-positive radius, density, speed; negative gravity or strength
  expect_error(kHeader + "0,2700,2000,1300,1.4e-4,0.05,7.2\n", "t.csv:2", "column 'impactor_radius': '0'");
  expect_error(kHeader + "0.05,2700,2000,1300,1.4e-4,0.05,-7.2\n", "t.csv:2",
               "column 'crater_radius': '-7.2'");
  expect_error(kHeader + "0.05,-2700,2000,1300,1.4e-4,0.05,7.2\n", "t.csv:2", "column 'impactor_density'");
  expect_error(kHeader + "0.05,2700,0,1300,1.4e-4,0.05,7.2\n", "t.csv:2", "column 'velocity'");
  expect_error(kHeader + "0.05,2700,2000,1300,-1,0.05,7.2\n", "t.csv:2", "column 'gravity'");
  expect_error(kHeader + "0.05,2700,2000,1300,1.4e-4,-0.05,7.2\n", "t.csv:2", "column 'strength'");
  // a row with too few or too many cells
  expect_error(kHeader + "0.05,2700,2000,1300,1.4e-4,0.05\n", "t.csv:2", "6 cells");
  expect_error(kHeader + "0.05,2700,2000,1300,1.4e-4,0.05,7.2,1\n", "t.csv:2", "8 cells");
  // sigma column present but a cell missing or not positive
  const std::string with_sigma =
      "impactor_radius,impactor_density,velocity,target_density,gravity,strength,crater_radius,crater_radius_"
      "sigma\n";
  expect_error(with_sigma + "0.05,2700,2000,1300,1.4e-4,0.05,7.2,0\n", "t.csv:2",
               "column 'crater_radius_sigma'");
  expect_error(with_sigma + "0.05,2700,2000,1300,1.4e-4,0.05,7.2,\n", "t.csv:2",
               "column 'crater_radius_sigma'");
}

TEST(RadiiTable, MissingFileIsReported) {
  EXPECT_THROW(cs::read_radii_csv("/nonexistent/radii.csv"), craterkit::InputError);
}

// A table as `craterkit sweep` writes it: the fit's columns, grouping columns (varied axes, some with
// dotted names), then the information columns run and growth_ended.
TEST(RadiiTable, SweepTableKeepsInformationAndGroupingColumnsAsWritten) {
  const std::string text =
      "# study cohesion-size, craterkit 0.1.0 (commit abc), command craterkit sweep study.toml\n"
      "impactor_radius,impactor_density,velocity,target_density,gravity,strength,crater_radius,"
      "crater_radius_sigma,friction,porosity,resolution,impact.grading,A_low,run,growth_ended\n"
      "0.0561297,2700,2000,1300,0.00014,0.05,7.21,0.25,0.55,0.5,18,none,1e-3,projectile_mass-2_cohesion-0.05,"
      "true\n"
      "0.0561297,2700,2000,1300,0.00014,0.5,4.8,0.2,0.50,0.5,18,linear,1e-3,projectile_mass-2_cohesion-0.5,"
      "false\n";
  const auto table = parse(text);
  ASSERT_EQ(table.rows.size(), 2u);
  EXPECT_EQ(table.group_columns,
            (std::vector<std::string>{"friction", "porosity", "resolution", "impact.grading", "A_low"}));
  EXPECT_TRUE(table.has_sigma());
  EXPECT_TRUE(table.has_run());
  EXPECT_TRUE(table.has_growth_ended());
  EXPECT_EQ(table.rows[0].group_values, (std::vector<std::string>{"0.55", "0.5", "18", "none", "1e-3"}));
  EXPECT_EQ(table.rows[1].group_values[0], "0.50");  // as written, not as a number
  EXPECT_EQ(table.rows[0].run.value(), "projectile_mass-2_cohesion-0.05");
  EXPECT_TRUE(table.rows[0].growth_ended.value());
  EXPECT_FALSE(table.rows[1].growth_ended.value());
  EXPECT_EQ(table.rows[1].line, 4);
  EXPECT_DOUBLE_EQ(table.rows[1].target.strength, 0.5);
  // Written and read again, every column survives.
  const auto again = parse(cs::format_radii_csv(table));
  EXPECT_EQ(again.group_columns, table.group_columns);
  EXPECT_EQ(again.rows[1].group_values, table.rows[1].group_values);
  EXPECT_EQ(again.rows[0].run, table.rows[0].run);
  EXPECT_EQ(again.rows[1].growth_ended, table.rows[1].growth_ended);
  // A table without them has none.
  const auto plain = parse(kHeader + kRow);
  EXPECT_TRUE(plain.group_columns.empty());
  EXPECT_FALSE(plain.has_run());
  EXPECT_FALSE(plain.has_growth_ended());
}

TEST(RadiiTable, MisspeltColumnsFailNamingThem) {
  // A misspelt required column: the missing column is named, with the header name that is close to it.
  expect_error(
      "impactor_radius,impactor_density,velocity,target_density,gravity,strenght,crater_radius\n" + kRow,
      "lacks the required column 'strength'", "did you mean 'strength' for header column 6 'strenght'");
  expect_error(
      "impactor_radius,impactor_density,velocty,target_density,gravity,strength,crater_radius\n" + kRow,
      "'velocity'", "'velocty'");
  // A misspelt optional or information column is refused rather than taken as a grouping column.
  expect_error(
      "impactor_radius,impactor_density,velocity,target_density,gravity,strength,crater_radius,"
      "crater_radius_sigm\n0.05,2700,2000,1300,1.4e-4,0.05,7.2,0.3\n",
      "'crater_radius_sigm'", "did you mean 'crater_radius_sigma'");
  expect_error(
      "impactor_radius,impactor_density,velocity,target_density,gravity,strength,crater_radius,"
      "growth_endd\n0.05,2700,2000,1300,1.4e-4,0.05,7.2,true\n",
      "'growth_endd'", "did you mean 'growth_ended'");
  // Case counts as a misspelling too.
  expect_error("Strength," + kHeader, "'Strength'", "did you mean 'strength'");
  // Short names far from every known name (but within 2 edits of `run`) are grouping columns.
  const auto table = parse("rho,mu," + kHeader + "a,b," + kRow);
  EXPECT_EQ(table.group_columns, (std::vector<std::string>{"rho", "mu"}));
  // A growth_ended that is not true/false, and a column without a name.
  expect_error(
      kHeader.substr(0, kHeader.size() - 1) + ",growth_ended\n" + kRow.substr(0, kRow.size() - 1) + ",yes\n",
      "t.csv:2: column 'growth_ended': 'yes'", "true or false");
  expect_error(kHeader.substr(0, kHeader.size() - 1) + ",,friction\n", "t.csv:1", "column 8 has no name");
}
