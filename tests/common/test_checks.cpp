// The checks of single numbers (common/checks.hpp): what passes, and the one wording of what fails.
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>

#include "craterkit/common/checks.hpp"
#include "craterkit/common/input_error.hpp"

namespace {

using craterkit::InputError;
constexpr double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string error_of(const std::function<void()>& check) {
  try {
    check();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Checks, RangeTextMarksOpenAndInfiniteEnds) {
  EXPECT_EQ(craterkit::range_text(0.0, 1.0), "[0, 1]");
  EXPECT_EQ(craterkit::range_text(0.0, 1.0, true), "(0, 1]");
  EXPECT_EQ(craterkit::range_text(0.0, 1.0, false, true), "[0, 1)");
  EXPECT_EQ(craterkit::range_text(0.0, kInf), "[0, inf)");
  EXPECT_EQ(craterkit::range_text(-kInf, -1.0, false, true), "(-inf, -1)");
  EXPECT_EQ(craterkit::range_text(0.0, 0.2, true), "(0, 0.2]");
}

TEST(Checks, InRangeNeedsAFiniteValueInsideTheInterval) {
  EXPECT_TRUE(craterkit::in_range(0.0, 0.0, 1.0));
  EXPECT_FALSE(craterkit::in_range(0.0, 0.0, 1.0, true));
  EXPECT_TRUE(craterkit::in_range(1.0, 0.0, 1.0));
  EXPECT_FALSE(craterkit::in_range(1.0, 0.0, 1.0, false, true));
  EXPECT_FALSE(craterkit::in_range(kNaN, -kInf, kInf));
  EXPECT_FALSE(craterkit::in_range(kInf, 0.0, kInf));
  EXPECT_TRUE(craterkit::in_range(1e300, 0.0, kInf));
}

TEST(Checks, PositiveAndNonNegative) {
  EXPECT_EQ(error_of([] { craterkit::require_positive(1e-300, "x"); }), "");
  EXPECT_EQ(error_of([] { craterkit::require_positive(0.0, "impact.projectile_mass"); }),
            "impact.projectile_mass: value 0 out of range: allowed (0, inf)");
  EXPECT_EQ(error_of([] { craterkit::require_positive(kInf, "x"); }),
            "x: value inf out of range: allowed (0, inf)");
  EXPECT_NE(error_of([] { craterkit::require_positive(kNaN, "x"); }), "");
  EXPECT_EQ(error_of([] { craterkit::require_non_negative(0.0, "x"); }), "");
  EXPECT_EQ(error_of([] { craterkit::require_non_negative(-2.5, "gravity"); }),
            "gravity: value -2.5 out of range: allowed [0, inf)");
  EXPECT_NE(error_of([] { craterkit::require_non_negative(kNaN, "x"); }), "");
}

TEST(Checks, InRangeNamesTheValueAndTheInterval) {
  EXPECT_EQ(error_of([] { craterkit::require_in_range(0.2, "g", 0.0, 0.2, true); }), "");
  EXPECT_EQ(error_of([] { craterkit::require_in_range(0.3, "impact.grading", 0.0, 0.2, true); }),
            "impact.grading: value 0.3 out of range: allowed (0, 0.2]");
  EXPECT_EQ(error_of([] { craterkit::require_in_range(90.0, "angle", 0.0, 90.0, false, true); }),
            "angle: value 90 out of range: allowed [0, 90)");
  EXPECT_EQ(craterkit::out_of_range_text(1.5, "> E_iv = 2"), "value 1.5 out of range: allowed > E_iv = 2");
}

}  // namespace
