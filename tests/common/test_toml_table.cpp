// The one TOML reader (common/toml_table.hpp): each getter's type and range checks, sub-tables and arrays
// of tables, the rejection of unknown keys, and messages that name the source, the dotted key, the value
// and what is allowed.
#include <gtest/gtest.h>

#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "craterkit/common/input_error.hpp"
#include "craterkit/common/toml_table.hpp"

namespace {

using craterkit::InputError;
using craterkit::TomlTable;
constexpr double kInf = std::numeric_limits<double>::infinity();

TomlTable parse(const std::string& text) {
  return TomlTable::parse(text, "t.toml");
}

// The message of the InputError that `read` throws on the table parsed from `text` ("" if none).
std::string error_of(const std::string& text, const std::function<void(TomlTable&)>& read) {
  try {
    TomlTable t = parse(text);
    read(t);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(TomlTable, SyntaxErrorsNameSourceLineAndColumn) {
  const std::string message = error_of("a = 1\nb = \n", [](TomlTable&) {});
  EXPECT_EQ(message.rfind("t.toml:2:", 0), 0u) << message;
  EXPECT_NE(message.find("TOML syntax error"), std::string::npos) << message;
}

TEST(TomlTable, ParseFileNamesAMissingFileAndReadsAnExistingOne) {
  const auto directory =
      std::filesystem::temp_directory_path() / ("craterkit_toml_table_" + std::to_string(::getpid()));
  std::filesystem::create_directories(directory);
  try {
    (void)TomlTable::parse_file(directory / "absent.toml");
    ADD_FAILURE() << "no error for a missing file";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("absent.toml"), std::string::npos) << e.what();
  }
  const auto path = directory / "present.toml";
  std::ofstream(path) << "x = 2\ny = \n";
  try {
    (void)TomlTable::parse_file(path);
    ADD_FAILURE() << "no error for a syntax error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path.string() + ":2:", 0), 0u) << e.what();
  }
  std::ofstream(path) << "x = 2\n";
  TomlTable t = TomlTable::parse_file(path);
  EXPECT_EQ(t.source(), path.string());
  EXPECT_EQ(t.required_number("x", 0.0, 10.0), 2.0);
  std::filesystem::remove_all(directory);
}

TEST(TomlTable, NumbersTakeIntegersFallbacksAndRanges) {
  TomlTable t = parse("a = 2\nb = 0.5\nc = 1\n");
  EXPECT_EQ(t.number("a", 7.0, 0.0, 10.0), 2.0);  // an integer is a number
  EXPECT_EQ(t.number("absent", 7.0, 0.0, 10.0), 7.0);
  EXPECT_EQ(t.optional_number("b", 0.0, 1.0, true, true), 0.5);
  EXPECT_FALSE(t.optional_number("none", 0.0, 1.0).has_value());
  EXPECT_EQ(t.required_number("c", 0.0, 1.0), 1.0);
  t.finish();
}

TEST(TomlTable, NumberRangeErrorsNameKeyValueAndInterval) {
  EXPECT_EQ(error_of("x = 5\n", [](TomlTable& r) { r.number("x", 0.0, 0.0, 1.0); }),
            "t.toml: x: value 5 out of range: allowed [0, 1]");
  EXPECT_EQ(error_of("x = 0\n", [](TomlTable& r) { r.number("x", 1.0, 0.0, 1.0, true); }),
            "t.toml: x: value 0 out of range: allowed (0, 1]");
  EXPECT_EQ(error_of("x = 90\n", [](TomlTable& r) { r.number("x", 1.0, 0.0, 90.0, true, true); }),
            "t.toml: x: value 90 out of range: allowed (0, 90)");
  EXPECT_EQ(error_of("x = -1\n", [](TomlTable& r) { r.required_number("x", 0.0, kInf, true); }),
            "t.toml: x: value -1 out of range: allowed (0, inf)");
  EXPECT_EQ(error_of("x = inf\n", [](TomlTable& r) { r.number("x", 1.0, -kInf, kInf); }),
            "t.toml: x: value inf out of range: allowed (-inf, inf)");
  EXPECT_NE(error_of("x = nan\n", [](TomlTable& r) { r.number("x", 1.0, -kInf, kInf); }).find("x: value nan"),
            std::string::npos);
  EXPECT_EQ(error_of("x = \"big\"\n", [](TomlTable& r) { r.number("x", 1.0, 0.0, 1.0); }),
            "t.toml: x: expected a number");
  EXPECT_EQ(error_of("", [](TomlTable& r) { r.required_number("x", 0.0, kInf); }),
            "t.toml: x: missing: a number in [0, inf)");
}

TEST(TomlTable, OutOfRangeUsesTheGettersWords) {
  EXPECT_EQ(error_of("[eos]\nE_cv = 1\n",
                     [](TomlTable& r) {
                       TomlTable eos = r.table("eos");
                       eos.out_of_range("E_cv", eos.required_number("E_cv", -kInf, kInf), "> E_iv = 2");
                     }),
            "t.toml: eos.E_cv: value 1 out of range: allowed > E_iv = 2");
}

TEST(TomlTable, IntegersAndBooleans) {
  TomlTable t = parse("n = 3\nflag = true\n");
  EXPECT_EQ(t.integer("n", 0, 0, 10), 3);
  EXPECT_EQ(t.integer("absent", 4, 0, 10), 4);
  EXPECT_TRUE(t.boolean("flag", false));
  EXPECT_FALSE(t.boolean("absent_flag", false));
  EXPECT_EQ(error_of("n = 11\n", [](TomlTable& r) { r.integer("n", 0, 0, 10); }),
            "t.toml: n: value 11 out of range: allowed [0, 10]");
  EXPECT_EQ(error_of("n = 1.5\n", [](TomlTable& r) { r.integer("n", 0, 0, 10); }),
            "t.toml: n: expected an integer");
  EXPECT_EQ(error_of("flag = \"yes\"\n", [](TomlTable& r) { r.boolean("flag", false); }),
            "t.toml: flag: expected true or false");
}

TEST(TomlTable, TextsCheckTypeEmptinessAndTheAllowedValues) {
  TomlTable t = parse("model = \"b\"\nname = \"x\"\n");
  EXPECT_EQ(t.text("model", "a", {"a", "b"}), "b");
  EXPECT_EQ(t.text("absent", "fallback"), "fallback");
  EXPECT_EQ(t.required_text("name", "a name"), "x");
  EXPECT_FALSE(t.optional_text("none").has_value());
  EXPECT_EQ(error_of("model = \"c\"\n",
                     [](TomlTable& r) {
                       r.text("model", "a", {"a", "b"});
                     }),
            "t.toml: model: value \"c\" not allowed: one of \"a\", \"b\"");
  EXPECT_EQ(error_of("model = \"\"\n", [](TomlTable& r) { r.text("model", "a"); }),
            "t.toml: model: must not be empty");
  EXPECT_EQ(error_of("model = 3\n", [](TomlTable& r) { r.text("model", "a"); }),
            "t.toml: model: expected a string");
  EXPECT_EQ(error_of("", [](TomlTable& r) { r.required_text("model", "the model"); }),
            "t.toml: model: missing: the model");
}

TEST(TomlTable, ArraysOfNumbersAndStrings) {
  TomlTable t = parse("v = [1, 2.5, 3]\nw = [1, inf]\nnames = [\"a\", \"b\"]\n");
  EXPECT_EQ(t.numbers("v").value(), (std::vector<double>{1.0, 2.5, 3.0}));
  EXPECT_EQ(t.required_numbers("w", 2, true)[1], kInf);
  EXPECT_FALSE(t.numbers("absent").has_value());
  EXPECT_EQ(t.texts("names").value(), (std::vector<std::string>{"a", "b"}));
  t.finish();
  EXPECT_EQ(error_of("v = [1, 2]\n", [](TomlTable& r) { r.numbers("v", 3); }),
            "t.toml: v: expected 3 numbers, got 2");
  EXPECT_EQ(error_of("v = 1\n", [](TomlTable& r) { r.numbers("v", 3); }),
            "t.toml: v: expected an array of 3 numbers");
  EXPECT_EQ(error_of("v = [1, \"a\"]\n", [](TomlTable& r) { r.numbers("v"); }),
            "t.toml: v: element 1 is not a number");
  EXPECT_EQ(error_of("v = [1, inf]\n", [](TomlTable& r) { r.numbers("v"); }),
            "t.toml: v: element 1 is not finite");
  EXPECT_EQ(error_of("", [](TomlTable& r) { r.required_numbers("v", 3); }),
            "t.toml: v: missing: an array of 3 numbers");
  EXPECT_EQ(error_of("", [](TomlTable& r) { r.required_numbers("v"); }),
            "t.toml: v: missing: an array of numbers");
  EXPECT_EQ(error_of("names = [\"a\", 2]\n", [](TomlTable& r) { r.texts("names"); }),
            "t.toml: names: element 1 is not a non-empty string");
}

TEST(TomlTable, SubTablesCarryDottedNames) {
  TomlTable t = parse("[outer]\nx = 1\n[outer.inner]\ny = 2\n");
  EXPECT_TRUE(t.is_table("outer"));
  TomlTable outer = t.table("outer");
  EXPECT_EQ(outer.name(), "outer");
  EXPECT_EQ(outer.key("x"), "outer.x");
  TomlTable inner = outer.table("inner");
  EXPECT_EQ(inner.name(), "outer.inner");
  EXPECT_EQ(inner.required_number("y", 0.0, 10.0), 2.0);
  EXPECT_EQ(outer.number("x", 0.0, 0.0, 10.0), 1.0);
  inner.finish();
  outer.finish();
  t.finish();
  EXPECT_EQ(error_of("[outer.inner]\ny = 20\n",
                     [](TomlTable& r) { r.table("outer").table("inner").number("y", 0.0, 0.0, 10.0); }),
            "t.toml: outer.inner.y: value 20 out of range: allowed [0, 10]");
}

TEST(TomlTable, AbsentTablesGiveFallbacksAndRequiredOnesAreNamed) {
  TomlTable t = parse("x = 1\n");
  EXPECT_FALSE(t.is_table("absent"));
  TomlTable absent = t.table("absent");
  EXPECT_EQ(absent.number("y", 4.0, 0.0, 10.0), 4.0);
  EXPECT_TRUE(absent.keys().empty());
  absent.finish();
  EXPECT_EQ(error_of("x = 1\n", [](TomlTable& r) { r.table("x"); }), "t.toml: x: must be a table ([x])");
  EXPECT_EQ(error_of("", [](TomlTable& r) { r.required_table("eos"); }),
            "t.toml: eos: missing: a table ([eos])");
  EXPECT_EQ(error_of("[a]\n", [](TomlTable& r) { r.table("a").required_table("b"); }),
            "t.toml: a.b: missing: a table ([a.b])");
  TomlTable present = parse("[eos]\nA = 1\n").required_table("eos");
  EXPECT_EQ(present.name(), "eos");
}

TEST(TomlTable, ArraysOfTablesAreNamedByIndex) {
  TomlTable t = parse("[[part]]\nr = 1\n[[part]]\nr = -1\n");
  std::vector<TomlTable> parts = t.tables("part");
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[1].name(), "part[1]");
  EXPECT_EQ(parts[0].required_number("r", 0.0, 10.0), 1.0);
  EXPECT_TRUE(t.tables("absent").empty());
  EXPECT_EQ(error_of("[[part]]\nr = 1\n[[part]]\nr = -1\n",
                     [](TomlTable& r) {
                       for (auto& part : r.tables("part")) part.required_number("r", 0.0, 10.0);
                     }),
            "t.toml: part[1].r: value -1 out of range: allowed [0, 10]");
  EXPECT_EQ(error_of("[[part]]\nr = 1\ncolour = 2\n",
                     [](TomlTable& r) {
                       for (auto& part : r.tables("part")) {
                         part.required_number("r", 0.0, 10.0);
                         part.finish();
                       }
                     }),
            "t.toml: unknown key part[0].colour (allowed here: r)");
  EXPECT_EQ(error_of("part = 3\n", [](TomlTable& r) { r.tables("part"); }),
            "t.toml: part: expected an array of tables ([[part]])");
  EXPECT_EQ(error_of("part = [1]\n", [](TomlTable& r) { r.tables("part"); }),
            "t.toml: part[0]: must be a table");
}

TEST(TomlTable, FinishRejectsKeysNoGetterAskedFor) {
  EXPECT_EQ(error_of("x = 1\ny = 2\nz = 3\n",
                     [](TomlTable& r) {
                       r.number("x", 0.0, 0.0, 10.0);
                       r.number("absent", 0.0, 0.0, 10.0);
                       r.accept("z");
                       r.finish();
                     }),
            "t.toml: unknown key y (allowed here: absent, x, z)");
  EXPECT_EQ(error_of("[s]\nx = 1\nq = 2\n",
                     [](TomlTable& r) {
                       TomlTable s = r.table("s");
                       s.number("x", 0.0, 0.0, 10.0);
                       s.finish();
                     }),
            "t.toml: unknown key s.q (allowed here: x)");
}

TEST(TomlTable, RejectUnknownChecksBeforeTheGettersAndCountsNothingAsRead) {
  // A misspelt key is named as unknown before the key it should have been is missed.
  EXPECT_EQ(error_of("radius = 1\n",
                     [](TomlTable& r) {
                       r.reject_unknown({"mean_radius", "name"});
                       r.required_number("mean_radius", 0.0, kInf);
                     }),
            "t.toml: unknown key radius (allowed here: mean_radius, name)");
  // An allowed key that no getter reads is still rejected by finish().
  EXPECT_EQ(error_of("slope = 1\ntable = \"f.csv\"\n",
                     [](TomlTable& r) {
                       r.reject_unknown({"slope", "table"});
                       r.required_text("table", "a file");
                       r.finish();
                     }),
            "t.toml: unknown key slope (allowed here: table)");
}

TEST(TomlTable, KeysAreSortedAndContainsDoesNotCountAsRead) {
  TomlTable t = parse("b = 1\na = 2\n[c]\n");
  EXPECT_EQ(t.keys(), (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_TRUE(t.contains("a"));
  EXPECT_FALSE(t.contains("d"));
  EXPECT_EQ(error_of("b = 1\n",
                     [](TomlTable& r) {
                       (void)r.contains("b");
                       r.finish();
                     }),
            "t.toml: unknown key b (no keys are allowed here)");
}

}  // namespace

// values_read(): every value the getters returned, defaults included, one sorted line per dotted key; two
// documents read alike list the same text exactly when the values seen were the same.
TEST(TomlTable, ValuesReadListsWhatTheGettersReturnedWithDefaults) {
  auto read = [](const std::string& text) {
    auto root = craterkit::TomlTable::parse(text, "test.toml");
    auto run = root.table("run");
    (void)run.number("end_time", 1.0, 0.0, 10.0);
    (void)run.integer("max_steps", 0, 0, 100);
    (void)run.boolean("log", true);
    (void)run.optional_text("label");
    (void)root.numbers("gravity", 3);
    return root.values_read();
  };
  EXPECT_EQ(
      read("gravity = [0, 0, -1]\n[run]\nend_time = 0.5\n"),
      "gravity = [0, 0, -1]\nrun.end_time = 0.5\nrun.label = (absent)\nrun.log = true\nrun.max_steps = 0\n");
  // Giving a default explicitly reads the same as leaving it out; another value does not.
  EXPECT_EQ(read("[run]\nend_time = 1\nmax_steps = 0\n"), read("[run]\n"));
  EXPECT_NE(read("[run]\nend_time = 0.1\n"), read("[run]\nend_time = 0.10000000000000002\n"));
}
