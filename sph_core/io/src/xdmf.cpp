#include "craterkit/sph/io/xdmf.hpp"

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <type_traits>

#include "craterkit/common/atomic_file.hpp"
#include "craterkit/common/input_error.hpp"
#include "craterkit/sph/particles/particles.hpp"
#include "snapshot_hdf5.hpp"

namespace craterkit::sph {
namespace {

std::string xml_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string exact(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

// XDMF NumberType and Precision of a field's element type. The uint64 particle id is declared as a
// signed 64-bit Int: the XDMF 2 readers have no unsigned 64-bit type, HDF5 converts on reading and
// ids stay far below 2^63.
template <class T>
std::pair<const char*, int> xdmf_number_type() {
  constexpr int precision = static_cast<int>(sizeof(T));
  if constexpr (std::is_floating_point_v<T>)
    return {"Float", precision};
  else if constexpr (std::is_signed_v<T>)
    return {precision == 1 ? "Char" : "Int", precision};
  else if constexpr (precision == 1)
    return {"UChar", 1};
  else if constexpr (precision == 8)
    return {"Int", 8};
  else
    return {"UInt", precision};
}

void data_item(std::ostringstream& xml, const std::string& indent, const std::string& dimensions,
               std::pair<const char*, int> type, const std::string& h5_reference, std::string_view dataset) {
  xml << indent << "<DataItem Dimensions=\"" << dimensions << "\" NumberType=\"" << type.first
      << "\" Precision=\"" << type.second << "\" Format=\"HDF\">" << xml_escape(h5_reference) << ":/"
      << dataset << "</DataItem>\n";
}

// One Uniform grid: the particles of one snapshot.
void uniform_grid(std::ostringstream& xml, const std::string& indent, const std::string& name,
                  const std::string& h5_reference, std::size_t count, double time, bool solid_fields) {
  const std::string n = std::to_string(count);
  const std::string in1 = indent + "  ";
  const std::string in2 = indent + "    ";
  xml << indent << "<Grid Name=\"" << xml_escape(name) << "\" GridType=\"Uniform\">\n";
  xml << in1 << "<Time Value=\"" << exact(time) << "\"/>\n";
  // Particles are vertices: one Polyvertex element per particle, connectivity 0..n-1.
  xml << in1 << "<Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n
      << "\" NodesPerElement=\"1\">\n";
  data_item(xml, in2, n, {"Int", 8}, h5_reference, "connectivity");
  xml << in1 << "</Topology>\n";
  xml << in1 << "<Geometry GeometryType=\"XYZ\">\n";
  data_item(xml, in2, n + " 3", {"Float", 8}, h5_reference, "position");
  xml << in1 << "</Geometry>\n";
  xml << in1 << "<Attribute Name=\"velocity\" AttributeType=\"Vector\" Center=\"Node\">\n";
  data_item(xml, in2, n + " 3", {"Float", 8}, h5_reference, "velocity");
  xml << in1 << "</Attribute>\n";
  if (solid_fields) {
    xml << in1 << "<Attribute Name=\"stress\" AttributeType=\"Tensor6\" Center=\"Node\">\n";
    data_item(xml, in2, n + " 6", {"Float", 8}, h5_reference, "stress");
    xml << in1 << "</Attribute>\n";
  }
  Particles layout;  // empty: only the field names and element types are needed
  layout.solid_fields = solid_fields;
  layout.for_each_field([&](std::string_view field, const auto& values) {
    using T = typename std::decay_t<decltype(values)>::value_type;
    xml << in1 << "<Attribute Name=\"" << field << "\" AttributeType=\"Scalar\" Center=\"Node\">\n";
    data_item(xml, in2, n, xdmf_number_type<T>(), h5_reference, field);
    xml << in1 << "</Attribute>\n";
  });
  xml << indent << "</Grid>\n";
}

SnapshotSummary summary_of(const std::filesystem::path& h5, const detail::ParticleFileHeader& header) {
  return {h5, header.time, header.step, static_cast<std::size_t>(header.particle_count), header.solid_fields};
}

const char* xdmf_prologue =
    "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n<Xdmf Version=\"2.0\">\n";

}  // namespace

std::string snapshot_xdmf(const std::string& h5_reference, std::size_t particle_count, double time,
                          bool solid_fields) {
  std::ostringstream xml;
  xml << xdmf_prologue << "  <Domain>\n";
  uniform_grid(xml, "    ", "particles", h5_reference, particle_count, time, solid_fields);
  xml << "  </Domain>\n</Xdmf>\n";
  return xml.str();
}

std::string time_series_xdmf(const std::vector<SnapshotSummary>& snapshots,
                             const std::filesystem::path& xdmf_directory) {
  std::ostringstream xml;
  xml << xdmf_prologue << "  <Domain>\n";
  xml << "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const auto& snapshot : snapshots) {
    const auto base = xdmf_directory.empty() ? std::filesystem::path(".") : xdmf_directory;
    const auto reference = std::filesystem::proximate(snapshot.h5, base);
    uniform_grid(xml, "      ", "step " + std::to_string(snapshot.step), reference.generic_string(),
                 snapshot.particle_count, snapshot.time, snapshot.solid_fields);
  }
  xml << "    </Grid>\n  </Domain>\n</Xdmf>\n";
  return xml.str();
}

SnapshotSummary summarize_snapshot(const std::filesystem::path& h5) {
  const auto header = detail::read_particle_file_header(h5);
  if (header.kind != detail::kind_snapshot) {
    throw InputError("cannot use " + h5.string() + " as a snapshot: its kind is '" + header.kind + "'");
  }
  return summary_of(h5, header);
}

std::vector<SnapshotSummary> find_snapshots(const std::filesystem::path& dir) {
  std::vector<SnapshotSummary> snapshots;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const auto& path = entry.path();
    // Skip temporary files of writes in progress (".name.tmp.PID") and anything not *.h5.
    if (!entry.is_regular_file() || path.extension() != ".h5" || path.filename().string().front() == '.')
      continue;
    try {
      auto header = detail::read_particle_file_header(path);
      if (header.kind == detail::kind_snapshot) {
        snapshots.push_back(summary_of(path, header));
      }
    } catch (const InputError&) {
      // Not a craterkit particle file: not part of the series.
    }
  }
  std::sort(snapshots.begin(), snapshots.end(), [](const SnapshotSummary& a, const SnapshotSummary& b) {
    return a.step != b.step ? a.step < b.step : a.time < b.time;
  });
  return snapshots;
}

void write_time_series_xdmf(const std::filesystem::path& xdmf,
                            const std::vector<SnapshotSummary>& snapshots) {
  write_text_atomically(xdmf, time_series_xdmf(snapshots, xdmf.parent_path()));
}

}  // namespace craterkit::sph
