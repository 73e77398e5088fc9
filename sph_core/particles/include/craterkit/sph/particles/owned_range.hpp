#pragma once
// A process's own particles among the copies of other processes' particles it holds (halos) in a run spread
// over several processes (docs/parallel.md): the index range [begin, end) of its particles.
#include <cstddef>

namespace craterkit::sph {

struct OwnedRange {
  std::size_t begin = 0, end = 0;
  [[nodiscard]] std::size_t size() const { return end - begin; }
};

}  // namespace craterkit::sph
