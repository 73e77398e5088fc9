// libFuzzer target: the radii table reader (craterkit fit's input) on arbitrary text.
#include <sstream>

#include "craterkit/common/input_error.hpp"
#include "craterkit/scaling/radii_table.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(craterkit::fuzz::input_text(data, size));
  try {
    (void)craterkit::scaling::parse_radii_csv(in, "fuzz.csv");
  } catch (const craterkit::InputError&) {
  }
  return 0;
}
