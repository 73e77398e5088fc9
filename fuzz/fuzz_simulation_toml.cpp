// libFuzzer target: the simulation configuration readers (impact and standard problems) on arbitrary text.
#include "craterkit/common/input_error.hpp"
#include "craterkit/impact/impact_config.hpp"
#include "craterkit/sph/run/standard_problem_config.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = craterkit::fuzz::input_text(data, size);
  try {
    (void)craterkit::impact::parse_impact_config(text, "fuzz.toml");
  } catch (const craterkit::InputError&) {
  }
  try {
    (void)craterkit::sph::parse_standard_problem_config(text, "fuzz.toml");
  } catch (const craterkit::InputError&) {
  }
  return 0;
}
