// libFuzzer target: the crater-count readers (.csv, .diam, .scc); the first byte picks the format.
#include "craterkit/chronology/crater_counts.hpp"
#include "craterkit/common/input_error.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const char* extensions[] = {".csv", ".diam", ".scc"};
  const auto path = craterkit::fuzz::input_file(data + 1, size - 1, extensions[data[0] % 3]);
  try {
    (void)craterkit::chronology::read_crater_counts(path.string());
  } catch (const craterkit::InputError&) {
  }
  return 0;
}
