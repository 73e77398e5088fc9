#pragma once
// Checkpoints for restart: the same HDF5 layout as a snapshot (snapshot.hpp), with `kind` =
// "checkpoint", without the visualisation copies (position/velocity) and without an XDMF sidecar.
// Every field is stored at full precision in its native type, so a run restarted from a checkpoint
// continues bit-for-bit (for the same thread count) provided the engine also stores in
// RunAttributes::numbers whatever else its state depends on (e.g. the current time step).
//
// Written atomically and flushed to disk before the rename: after a crash the file under the final
// name is either the previous complete checkpoint or the new complete one.
#include <filesystem>

#include "craterkit/sph/io/snapshot.hpp"
#include "craterkit/sph/particles/particles.hpp"

namespace craterkit::sph {

void write_checkpoint(const std::filesystem::path& h5, const Particles& particles,
                      const RunAttributes& attributes);

// Reads a checkpoint (a snapshot is accepted too: it holds every field at full precision).
// Errors (missing file, corrupt or truncated file, missing field, wrong type or length) are
// craterkit::InputError naming the path and the problem.
Particles read_checkpoint(const std::filesystem::path& h5, RunAttributes* attributes = nullptr);

}  // namespace craterkit::sph
