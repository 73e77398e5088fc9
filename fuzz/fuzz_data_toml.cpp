// libFuzzer target: the data-file readers (materials, bodies, impactor populations) on arbitrary files.
#include "craterkit/chronology/body.hpp"
#include "craterkit/chronology/population.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/sph/io/material_file.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = craterkit::fuzz::input_file(data, size, ".toml");
  try {
    (void)craterkit::sph::load_material(path.string());
  } catch (const craterkit::InputError&) {
  }
  try {
    (void)craterkit::chronology::load_body_file(path);
  } catch (const craterkit::InputError&) {
  }
  try {
    (void)craterkit::chronology::load_population_file(path);
  } catch (const craterkit::InputError&) {
  }
  return 0;
}
