#pragma once
// Internal: the HDF5 particle-file layout shared by snapshots and checkpoints (HDF5 1.10 C API),
// with RAII handles and the HDF5 error stack silenced (errors become exceptions with context).
#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "craterkit/sph/io/snapshot.hpp"
#include "craterkit/sph/particles/particles.hpp"

namespace craterkit::sph::detail {

inline constexpr const char* particle_file_format = "craterkit-particles";
inline constexpr std::int32_t particle_file_version = 1;
inline constexpr const char* kind_snapshot = "snapshot";
inline constexpr const char* kind_checkpoint = "checkpoint";

struct ParticleFileOptions {
  const char* kind = kind_snapshot;
  bool visualisation_vectors = false;  // also write interleaved position/velocity (n x 3) and stress (n x 6)
  int compression = 0;                 // deflate level of every dataset, 0 (none) .. 9
  bool integrity_record = true;        // false: a file as earlier versions wrote it (for tests and fuzzing)
};

// Writes the particle file at `path` (not atomically: callers write to a temporary sibling) and
// forces it to disk (fsync) before returning.
void write_particle_file(const std::filesystem::path& path, const Particles& particles,
                         const RunAttributes& attributes, const ParticleFileOptions& options);

// Reads every field; errors are InputError naming `path`.
Particles read_particle_file(const std::filesystem::path& path, RunAttributes* attributes);

// Root attributes only. kind receives the `kind` attribute.
struct ParticleFileHeader {
  std::string kind;
  double time = 0;
  std::uint64_t step = 0;
  std::uint64_t particle_count = 0;
  bool solid_fields = false;  // holds the solid-mechanics group (Particles::solid_fields)
};
ParticleFileHeader read_particle_file_header(const std::filesystem::path& path);

// Writes the integrity record (user block: length and hash of the rest) of a closed particle file.
void seal_particle_file(const std::filesystem::path& path);

// Flushes a written file to stable storage (fsync); throws std::runtime_error on failure.
void sync_to_disk(const std::filesystem::path& file);
// Flushes a directory's entries (a rename) to stable storage; best effort, errors are ignored.
void sync_directory(const std::filesystem::path& directory) noexcept;

}  // namespace craterkit::sph::detail
