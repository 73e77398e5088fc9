#include "craterkit/sph/io/checkpoint.hpp"

#include "craterkit/common/atomic_file.hpp"
#include "snapshot_hdf5.hpp"

namespace craterkit::sph {

void write_checkpoint(const std::filesystem::path& h5, const Particles& particles,
                      const RunAttributes& attributes) {
  const detail::ParticleFileOptions options{detail::kind_checkpoint, /*visualisation_vectors=*/false};
  // write_particle_file flushes the temporary file to disk before the rename, so after a crash the
  // final name holds either the previous or the new checkpoint, complete.
  write_atomically(h5, [&](const std::filesystem::path& tmp) {
    detail::write_particle_file(tmp, particles, attributes, options);
  });
  detail::sync_directory(h5.parent_path());  // make the rename itself durable
}

Particles read_checkpoint(const std::filesystem::path& h5, RunAttributes* attributes) {
  return detail::read_particle_file(h5, attributes);
}

}  // namespace craterkit::sph
