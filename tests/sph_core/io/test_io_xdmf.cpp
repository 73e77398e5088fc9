// XDMF sidecars: well-formed XML (parsed back here by a small strict parser), the Polyvertex /
// XYZ / attribute structure ParaView and VisIt expect, and every referenced dataset present in the
// HDF5 file with the declared shape and type.
#include <hdf5.h>

#include <cctype>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "craterkit/sph/io/checkpoint.hpp"
#include "craterkit/sph/io/snapshot.hpp"
#include "craterkit/sph/io/xdmf.hpp"
#include "sph_core/test_io_scratch_directory.hpp"

namespace sph = craterkit::sph;
namespace fs = std::filesystem;
using craterkit::test::ScratchDirectory;

namespace {

// ---- a minimal strict XML parser: elements, attributes, text, comments, <?...?> and <!DOCTYPE> ----
struct Element {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;
  std::vector<std::unique_ptr<Element>> children;

  [[nodiscard]] std::vector<const Element*> all(const std::string& child_name) const {
    std::vector<const Element*> found;
    for (const auto& child : children) {
      if (child->name == child_name) found.push_back(child.get());
    }
    return found;
  }
  [[nodiscard]] const Element& one(const std::string& child_name) const {
    const auto found = all(child_name);
    if (found.size() != 1) {
      throw std::runtime_error("<" + name + "> has " + std::to_string(found.size()) + " <" + child_name +
                               ">");
    }
    return *found.front();
  }
  [[nodiscard]] std::string attribute(const std::string& key) const {
    const auto it = attributes.find(key);
    if (it == attributes.end()) throw std::runtime_error("<" + name + "> has no attribute " + key);
    return it->second;
  }
};

class XmlParser {
 public:
  explicit XmlParser(std::string text) : s_(std::move(text)) {}

  std::unique_ptr<Element> parse_document() {
    skip_misc();
    auto root = parse_element();
    skip_misc();
    if (pos_ != s_.size()) fail("content after the root element");
    return root;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("XML error at offset " + std::to_string(pos_) + ": " + what);
  }
  bool starts(const char* prefix) const { return s_.compare(pos_, std::strlen(prefix), prefix) == 0; }
  void skip_space() {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
  }
  void skip_until(const char* end) {
    const auto found = s_.find(end, pos_);
    if (found == std::string::npos) fail(std::string("unterminated, expected ") + end);
    pos_ = found + std::strlen(end);
  }
  void skip_misc() {  // prolog, doctype, comments, white space
    for (;;) {
      skip_space();
      if (starts("<?")) {
        skip_until("?>");
      } else if (starts("<!--")) {
        skip_until("-->");
      } else if (starts("<!DOCTYPE")) {
        skip_until(">");
      } else {
        return;
      }
    }
  }
  std::string name() {
    const std::size_t start = pos_;
    while (pos_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[pos_])) || s_[pos_] == '_' ||
                                s_[pos_] == ':' || s_[pos_] == '-' || s_[pos_] == '.')) {
      ++pos_;
    }
    if (pos_ == start) fail("expected a name");
    return s_.substr(start, pos_ - start);
  }
  std::string unescape(const std::string& raw) const {
    std::string out;
    for (std::size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] == '<') fail("raw '<' in text or attribute");
      if (raw[i] != '&') {
        out += raw[i];
        continue;
      }
      const auto end = raw.find(';', i);
      if (end == std::string::npos) fail("unterminated entity");
      const std::string entity = raw.substr(i + 1, end - i - 1);
      static const std::map<std::string, char> entities{
          {"amp", '&'}, {"lt", '<'}, {"gt", '>'}, {"quot", '"'}, {"apos", '\''}};
      const auto it = entities.find(entity);
      if (it == entities.end()) fail("unknown entity &" + entity + ";");
      out += it->second;
      i = end;
    }
    return out;
  }
  std::unique_ptr<Element> parse_element() {
    if (!starts("<")) fail("expected '<'");
    ++pos_;
    auto element = std::make_unique<Element>();
    element->name = name();
    for (;;) {
      skip_space();
      if (starts("/>")) {
        pos_ += 2;
        return element;
      }
      if (starts(">")) {
        ++pos_;
        break;
      }
      const std::string key = name();
      skip_space();
      if (!starts("=")) fail("expected '=' after attribute " + key);
      ++pos_;
      skip_space();
      if (!starts("\"")) fail("attribute values must be double-quoted");
      const auto end = s_.find('"', pos_ + 1);
      if (end == std::string::npos) fail("unterminated attribute value");
      if (!element->attributes.emplace(key, unescape(s_.substr(pos_ + 1, end - pos_ - 1))).second) {
        fail("duplicate attribute " + key);
      }
      pos_ = end + 1;
    }
    for (;;) {  // content
      if (starts("</")) {
        pos_ += 2;
        if (name() != element->name) fail("mismatched closing tag for <" + element->name + ">");
        skip_space();
        if (!starts(">")) fail("expected '>'");
        ++pos_;
        return element;
      }
      if (starts("<!--")) {
        skip_until("-->");
      } else if (starts("<")) {
        element->children.push_back(parse_element());
      } else {
        const auto end = s_.find('<', pos_);
        if (end == std::string::npos) fail("unterminated element <" + element->name + ">");
        element->text += unescape(s_.substr(pos_, end - pos_));
        pos_ = end;
      }
    }
  }

  std::string s_;
  std::size_t pos_ = 0;
};

std::unique_ptr<Element> parse_file(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return XmlParser(text.str()).parse_document();
}

std::string trim(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t\n");
  const auto end = text.find_last_not_of(" \t\n");
  return begin == std::string::npos ? "" : text.substr(begin, end - begin + 1);
}

// Checks one <DataItem> against the HDF5 file it points at: reference "file.h5:/dataset" resolves
// relative to `xml_dir`, the dataset exists, its shape equals Dimensions and its stored type is
// exactly NumberType/Precision (except the documented Int 8 for the unsigned 64-bit id).
void check_data_item(const Element& item, const fs::path& xml_dir, const std::string& expected_dataset,
                     const std::string& expected_dimensions) {
  SCOPED_TRACE(expected_dataset);
  EXPECT_EQ(item.attribute("Format"), "HDF");
  EXPECT_EQ(item.attribute("Dimensions"), expected_dimensions);
  const std::string reference = trim(item.text);
  const auto colon = reference.find(":/");
  ASSERT_NE(colon, std::string::npos) << reference;
  const fs::path h5 = xml_dir / reference.substr(0, colon);
  const std::string dataset = reference.substr(colon + 2);
  EXPECT_EQ(dataset, expected_dataset);

  const hid_t file = H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0) << h5;
  const hid_t data = H5Dopen2(file, dataset.c_str(), H5P_DEFAULT);
  ASSERT_GE(data, 0) << reference;
  const hid_t space = H5Dget_space(data);
  hsize_t dims[2] = {0, 0};
  const int rank = H5Sget_simple_extent_dims(space, dims, nullptr);
  const std::string shape =
      rank == 1 ? std::to_string(dims[0]) : std::to_string(dims[0]) + " " + std::to_string(dims[1]);
  EXPECT_EQ(shape, expected_dimensions);
  const hid_t type = H5Dget_type(data);
  const std::string number_type = item.attribute("NumberType");
  const auto precision = static_cast<std::size_t>(std::stoi(item.attribute("Precision")));
  EXPECT_EQ(H5Tget_size(type), precision);
  if (number_type == "Float") {
    EXPECT_EQ(H5Tget_class(type), H5T_FLOAT);
  } else {
    EXPECT_EQ(H5Tget_class(type), H5T_INTEGER);
    const bool declared_unsigned = number_type == "UInt" || number_type == "UChar";
    if (dataset != "id") {
      EXPECT_EQ(H5Tget_sign(type) == H5T_SGN_NONE, declared_unsigned);
    }
  }
  H5Tclose(type);
  H5Sclose(space);
  H5Dclose(data);
  H5Fclose(file);
}

std::vector<std::string> field_names(bool solid_fields) {
  std::vector<std::string> names;
  sph::Particles layout;
  layout.solid_fields = solid_fields;
  layout.for_each_field([&](std::string_view name, const auto&) { names.emplace_back(name); });
  return names;
}

// Checks a Uniform particle grid; returns its time.
// solid_fields: whether the snapshot holds the solid-mechanics group (Particles::solid_fields).
double check_particle_grid(const Element& grid, const fs::path& xml_dir, std::size_t n,
                           bool solid_fields = true) {
  EXPECT_EQ(grid.attribute("GridType"), "Uniform");
  const std::string count = std::to_string(n);
  const Element& topology = grid.one("Topology");
  EXPECT_EQ(topology.attribute("TopologyType"), "Polyvertex");
  EXPECT_EQ(topology.attribute("NumberOfElements"), count);
  EXPECT_EQ(topology.attribute("NodesPerElement"), "1");
  check_data_item(topology.one("DataItem"), xml_dir, "connectivity", count);
  const Element& geometry = grid.one("Geometry");
  EXPECT_EQ(geometry.attribute("GeometryType"), "XYZ");
  check_data_item(geometry.one("DataItem"), xml_dir, "position", count + " 3");

  std::map<std::string, const Element*> attributes;
  for (const Element* attribute : grid.all("Attribute")) {
    EXPECT_TRUE(attributes.emplace(attribute->attribute("Name"), attribute).second) << "duplicate";
    EXPECT_EQ(attribute->attribute("Center"), "Node");
  }
  if (attributes.count("velocity") != 1) {
    ADD_FAILURE() << "no velocity vector";
    return -1;
  }
  EXPECT_EQ(attributes["velocity"]->attribute("AttributeType"), "Vector");
  check_data_item(attributes["velocity"]->one("DataItem"), xml_dir, "velocity", count + " 3");
  const auto names = field_names(solid_fields);
  // every field + the velocity vector (+ the stress tensor with solid fields)
  EXPECT_EQ(attributes.size(), names.size() + (solid_fields ? 2 : 1));
  EXPECT_EQ(attributes.count("stress"), solid_fields ? 1u : 0u);
  if (solid_fields && attributes.count("stress") == 1) {
    EXPECT_EQ(attributes["stress"]->attribute("AttributeType"), "Tensor6");
    check_data_item(attributes["stress"]->one("DataItem"), xml_dir, "stress", count + " 6");
  }
  for (const auto& name : names) {
    if (attributes.count(name) == 0) {
      ADD_FAILURE() << "no attribute for field " << name;
      continue;
    }
    EXPECT_EQ(attributes[name]->attribute("AttributeType"), "Scalar");
    check_data_item(attributes[name]->one("DataItem"), xml_dir, name, count);
  }
  return std::stod(grid.one("Time").attribute("Value"));
}

sph::Particles lattice(std::size_t n) {
  sph::Particles p;
  p.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    p.id[i] = i;
    p.x[i] = static_cast<double>(i % 10);
    p.y[i] = static_cast<double>((i / 10) % 10);
    p.z[i] = static_cast<double>(i / 100);
    p.density[i] = 2700;
  }
  return p;
}

}  // namespace

TEST(IoXdmf, ParserRejectsMalformedXml) {
  EXPECT_THROW(XmlParser("<a><b></a>").parse_document(), std::runtime_error);
  EXPECT_THROW(XmlParser("<a x=1/>").parse_document(), std::runtime_error);
  EXPECT_THROW(XmlParser("<a>&bogus;</a>").parse_document(), std::runtime_error);
  EXPECT_THROW(XmlParser("<a/><b/>").parse_document(), std::runtime_error);
  EXPECT_NO_THROW(XmlParser("<?xml version=\"1.0\" ?>\n<a k=\"&lt;\"><b/>t&amp;</a>\n").parse_document());
}

TEST(IoXdmf, SnapshotSidecarDescribesEveryDataset) {
  ScratchDirectory dir("xdmf_sidecar");
  sph::RunAttributes attributes;
  attributes.time = 0.1 + 0.2;
  sph::write_snapshot(dir / "snap_000007.h5", lattice(250), attributes);
  const auto xml = parse_file(dir / "snap_000007.xdmf");
  ASSERT_EQ(xml->name, "Xdmf");
  EXPECT_EQ(xml->attribute("Version"), "2.0");
  const Element& grid = xml->one("Domain").one("Grid");
  const double time = check_particle_grid(grid, dir.path(), 250);
  EXPECT_EQ(time, 0.1 + 0.2);  // written with 17 digits: exact
  // The vertex cells are the particles in order: connectivity 0..n-1.
  const hid_t file = H5Fopen((dir / "snap_000007.h5").c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const hid_t data = H5Dopen2(file, "connectivity", H5P_DEFAULT);
  std::vector<long long> connectivity(250, -1);
  ASSERT_GE(H5Dread(data, H5T_NATIVE_LLONG, H5S_ALL, H5S_ALL, H5P_DEFAULT, connectivity.data()), 0);
  H5Dclose(data);
  H5Fclose(file);
  for (std::size_t i = 0; i < connectivity.size(); ++i) EXPECT_EQ(connectivity[i], static_cast<long long>(i));
  // The reference is the bare file name, so the directory can be moved.
  EXPECT_EQ(trim(grid.one("Geometry").one("DataItem").text), "snap_000007.h5:/position");
}

// A fluid run drops the solid-mechanics group: its sidecar must not point at datasets that are not there.
TEST(IoXdmf, FluidSnapshotSidecarListsOnlyTheFieldsItHolds) {
  ScratchDirectory dir("xdmf_fluid");
  auto particles = lattice(40);
  particles.set_solid_fields(false);
  sph::write_snapshot(dir / "snap_000001.h5", particles, {});
  const auto xml = parse_file(dir / "snap_000001.xdmf");
  check_particle_grid(xml->one("Domain").one("Grid"), dir.path(), 40, /*solid_fields=*/false);
  std::size_t solid_group = 0;
  particles.for_each_solid_field([&](std::string_view, const auto&) { ++solid_group; });
  EXPECT_EQ(xml->one("Domain").one("Grid").all("Attribute").size(),
            field_names(true).size() + 1 - solid_group);
  sph::write_time_series_xdmf(dir / "run.xdmf", sph::find_snapshots(dir.path()));
  const auto series = parse_file(dir / "run.xdmf");
  check_particle_grid(*series->one("Domain").one("Grid").all("Grid").at(0), dir.path(), 40, false);
}

TEST(IoXdmf, FileNamesAreEscaped) {
  ScratchDirectory dir("xdmf_escape");
  sph::write_snapshot(dir / "a&b<c>.h5", lattice(3), {});
  const auto xml = parse_file(dir / "a&b<c>.xdmf");
  check_particle_grid(xml->one("Domain").one("Grid"), dir.path(), 3);
}

TEST(IoXdmf, TimeSeriesCollectsSnapshotsInStepOrder) {
  ScratchDirectory dir("xdmf_series");
  fs::create_directories(dir / "snapshots");
  const std::vector<std::pair<std::uint64_t, std::size_t>> steps{{20, 300}, {0, 100}, {10, 200}};
  for (const auto& [step, n] : steps) {
    sph::RunAttributes attributes;
    attributes.step = step;
    attributes.time = 0.001 * static_cast<double>(step);
    sph::write_snapshot(dir / "snapshots" / ("snap_" + std::to_string(step) + ".h5"), lattice(n), attributes);
  }
  // Neither a checkpoint nor a foreign .h5 file belongs to the series.
  sph::write_checkpoint(dir / "snapshots" / "checkpoint.h5", lattice(5), {});
  std::ofstream(dir / "snapshots" / "notes.h5") << "not hdf5";

  const auto found = sph::find_snapshots(dir / "snapshots");
  ASSERT_EQ(found.size(), 3u);
  EXPECT_EQ(found[0].step, 0u);
  EXPECT_EQ(found[1].step, 10u);
  EXPECT_EQ(found[2].step, 20u);
  EXPECT_EQ(found[2].particle_count, 300u);

  // The series file lives one directory up: references are relative to it.
  sph::write_time_series_xdmf(dir / "run.xdmf", found);
  const auto xml = parse_file(dir / "run.xdmf");
  const Element& collection = xml->one("Domain").one("Grid");
  EXPECT_EQ(collection.attribute("GridType"), "Collection");
  EXPECT_EQ(collection.attribute("CollectionType"), "Temporal");
  const auto grids = collection.all("Grid");
  ASSERT_EQ(grids.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(check_particle_grid(*grids[k], dir.path(), found[k].particle_count), found[k].time);
  }
  EXPECT_EQ(trim(grids[1]->one("Geometry").one("DataItem").text), "snapshots/snap_10.h5:/position");
}
