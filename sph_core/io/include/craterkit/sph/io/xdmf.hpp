#pragma once
// XDMF (version 2) descriptions of particle snapshots, read by ParaView ("XDMF Reader" and the
// Xdmf3 readers) and VisIt. The heavy data stays in the HDF5 snapshot; the XML only points at it.
// Each snapshot is a Uniform grid: Polyvertex topology (one vertex cell per particle, explicit
// `connectivity` dataset), XYZ geometry from the interleaved `position` dataset, a `velocity` vector
// attribute and a scalar node attribute for every particle field. Datasets are referenced by file name only
// (relative to the XML file), so a run directory can be moved or copied as a whole.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace craterkit::sph {

// What an XDMF grid needs to know about one snapshot file.
struct SnapshotSummary {
  std::filesystem::path h5;  // the snapshot file
  double time = 0;           // s
  std::uint64_t step = 0;
  std::size_t particle_count = 0;
  bool solid_fields = false;  // holds the solid-mechanics group (Particles::solid_fields)
};

// The XDMF document for one snapshot; h5_reference is the file name written into the XML.
std::string snapshot_xdmf(const std::string& h5_reference, std::size_t particle_count, double time,
                          bool solid_fields);

// A temporal collection over several snapshots (in the given order), for a whole run.
// Each snapshot is referenced relative to the directory of the XML file.
std::string time_series_xdmf(const std::vector<SnapshotSummary>& snapshots,
                             const std::filesystem::path& xdmf_directory);

// Reads time, step and particle count from a snapshot's attributes (cheap: no datasets are read).
// Throws craterkit::InputError if it is not a craterkit snapshot.
SnapshotSummary summarize_snapshot(const std::filesystem::path& h5);

// Every craterkit snapshot (kind "snapshot") directly inside dir, sorted by step then time.
// Other .h5 files (checkpoints, foreign files) are skipped.
std::vector<SnapshotSummary> find_snapshots(const std::filesystem::path& dir);

// Writes (atomically) the time-series XDMF over the given snapshots, e.g.
//   write_time_series_xdmf(out / "snapshots.xdmf", find_snapshots(out));
// after each snapshot: on resume this picks up the snapshots written before the restart.
void write_time_series_xdmf(const std::filesystem::path& xdmf, const std::vector<SnapshotSummary>& snapshots);

}  // namespace craterkit::sph
