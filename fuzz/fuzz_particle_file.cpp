// libFuzzer target: the particle-file reader (snapshots and checkpoints) on arbitrary files.
// Files without an integrity record (those of earlier versions: they start with the HDF5 signature) go
// straight to the HDF5 library, which crashes on some damaged ones (docs/reliability.md, "Fuzzing"); they
// are skipped unless CRATERKIT_FUZZ_LEGACY=1, so that the target fuzzes what craterkit's own files meet.
#include <cstdlib>
#include <cstring>

#include "craterkit/common/input_error.hpp"
#include "craterkit/sph/io/checkpoint.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool legacy = std::getenv("CRATERKIT_FUZZ_LEGACY") != nullptr;
  if (!legacy && size >= 8 && std::memcmp(data, "\x89HDF\r\n\x1a\n", 8) == 0) return 0;
  const auto path = craterkit::fuzz::input_file(data, size, ".h5");
  try {
    craterkit::sph::RunAttributes attributes;
    (void)craterkit::sph::read_checkpoint(path, &attributes);
  } catch (const craterkit::InputError&) {
  }
  return 0;
}
