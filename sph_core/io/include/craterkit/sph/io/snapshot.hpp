#pragma once
// HDF5 snapshots of the particle set, with an XDMF sidecar so that ParaView and VisIt open them.
//
// One file per snapshot. Every field of Particles::for_each_field is a 1-D dataset at the root of
// the file, named as there and stored in its native type (doubles stay doubles), so a snapshot read
// back is bit-for-bit the particle set that was written. For visualisation the snapshot also holds
// `position` and `velocity` (n x 3, interleaved copies of x/y/z and vx/vy/vz) and `connectivity`
// (0..n-1), which the XDMF sidecar uses as geometry, velocity vector and vertex cells; readers of
// the fields ignore them. Root attributes: `format`,
// `kind`, `format_version`, `particle_count`, `time` (s), `step`, and every RunAttributes entry.
// The layout is described for users in docs/output.md.
//
// Files are written atomically: to a temporary name beside the target, flushed to disk, then renamed.
// A failed or killed write never leaves a partial file under the final name.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>

#include "craterkit/sph/particles/particles.hpp"

namespace craterkit::sph {

// Scalar run metadata stored as root attributes of a snapshot or checkpoint (and restored on read).
// numbers: doubles (exact round trip), texts: UTF-8 strings. Names must not be one of the reserved
// attribute names (format, kind, format_version, particle_count, time, step) and must not occur in both.
struct RunAttributes {
  double time = 0;         // simulated time, s
  std::uint64_t step = 0;  // number of completed time steps
  std::map<std::string, double> numbers;
  std::map<std::string, std::string> texts;

  // The value of a required attribute; a missing one is a craterkit::InputError "<source>: attribute <key>
  // missing".
  [[nodiscard]] double number(const std::string& key, const std::string& source) const;
  [[nodiscard]] const std::string& text(const std::string& key, const std::string& source) const;
};

// Writes h5 (atomically) and its XDMF sidecar (xdmf_sidecar_path(h5), also atomically).
// Throws std::invalid_argument if the fields of `particles` differ in length or an attribute name is
// reserved, std::runtime_error if the file cannot be written; in both cases nothing is left under
// either final name that was not there before.
// compression: deflate level 0 (none) .. 9 of every dataset (readers need nothing special).
void write_snapshot(const std::filesystem::path& h5, const Particles& particles,
                    const RunAttributes& attributes, int compression = 0);

// Reads every field of a snapshot (or checkpoint). Throws craterkit::InputError naming the path and
// what is wrong if the file is missing, damaged (its length or checksum differ from the integrity record
// written with it), not HDF5, not a craterkit particle file, or a field is missing or has the wrong type
// or length. Fills *attributes when given.
Particles read_snapshot(const std::filesystem::path& h5, RunAttributes* attributes = nullptr);

// Particle files carry an integrity record (length and checksum) in their HDF5 user block, which every
// reader checks before HDF5 parses the file (docs/output.md). A file changed on purpose by another program
// (h5py, h5repack) no longer matches it; this writes the record anew for the file as it is now.
void reseal_particle_file(const std::filesystem::path& h5);

// "run/snap_000012.h5" -> "run/snap_000012.xdmf".
std::filesystem::path xdmf_sidecar_path(const std::filesystem::path& h5);

// Physical unit of a particle field as written to the `units` attribute of its dataset
// ("m", "kg/m^3", "1" for dimensionless numbers, "" for identifiers, flags and unknown names).
std::string field_unit(std::string_view field_name);

}  // namespace craterkit::sph
