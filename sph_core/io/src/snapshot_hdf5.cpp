// HDF5 particle files (snapshots and checkpoints) with the HDF5 1.10 C API.
#include "snapshot_hdf5.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "craterkit/common/input_error.hpp"

namespace craterkit::sph::detail {
namespace {

// Owns an HDF5 identifier and closes it with the matching H5?close.
class Handle {
 public:
  Handle(hid_t id, herr_t (*closer)(hid_t)) : id_(id), close_(closer) {}
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept : id_(other.id_), close_(other.close_) { other.id_ = -1; }
  Handle& operator=(Handle&&) = delete;
  [[nodiscard]] hid_t get() const { return id_; }
  [[nodiscard]] bool valid() const { return id_ >= 0; }
  // Closes now and reports failure (H5Fclose is where buffered data reaches the file).
  [[nodiscard]] bool close() {
    const herr_t status = id_ >= 0 ? close_(id_) : 0;
    id_ = -1;
    return status >= 0;
  }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

// HDF5 prints its error stack to stderr by default; we turn every failure into an exception with
// context instead, so silence the printing for the duration of one call (restored afterwards).
class SilenceHdf5Errors {
 public:
  SilenceHdf5Errors() {
    H5Eget_auto2(H5E_DEFAULT, &function_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~SilenceHdf5Errors() { H5Eset_auto2(H5E_DEFAULT, function_, data_); }
  SilenceHdf5Errors(const SilenceHdf5Errors&) = delete;
  SilenceHdf5Errors& operator=(const SilenceHdf5Errors&) = delete;

 private:
  H5E_auto2_t function_ = nullptr;
  void* data_ = nullptr;
};

// Dependent false for the static_asserts below (a class template: clang reports an unused variable
// template here, since its uses sit in discarded branches).
template <class>
struct UnsupportedFieldType : std::false_type {};

// Memory (native) and file (little-endian standard) types of the field element types. A field of
// another type added to Particles fails to compile here, with this message.
template <class T>
hid_t memory_type() {
  if constexpr (std::is_same_v<T, double>)
    return H5T_NATIVE_DOUBLE;
  else if constexpr (std::is_same_v<T, float>)
    return H5T_NATIVE_FLOAT;
  else if constexpr (std::is_same_v<T, std::uint64_t>)
    return H5T_NATIVE_UINT64;
  else if constexpr (std::is_same_v<T, std::uint32_t>)
    return H5T_NATIVE_UINT32;
  else if constexpr (std::is_same_v<T, std::uint16_t>)
    return H5T_NATIVE_UINT16;
  else if constexpr (std::is_same_v<T, std::uint8_t>)
    return H5T_NATIVE_UINT8;
  else if constexpr (std::is_same_v<T, std::int64_t>)
    return H5T_NATIVE_INT64;
  else if constexpr (std::is_same_v<T, std::int32_t>)
    return H5T_NATIVE_INT32;
  else if constexpr (std::is_same_v<T, std::int16_t>)
    return H5T_NATIVE_INT16;
  else if constexpr (std::is_same_v<T, std::int8_t>)
    return H5T_NATIVE_INT8;
  else
    static_assert(UnsupportedFieldType<T>::value, "particle field element type without an HDF5 mapping");
}
template <class T>
hid_t file_type() {
  if constexpr (std::is_same_v<T, double>)
    return H5T_IEEE_F64LE;
  else if constexpr (std::is_same_v<T, float>)
    return H5T_IEEE_F32LE;
  else if constexpr (std::is_same_v<T, std::uint64_t>)
    return H5T_STD_U64LE;
  else if constexpr (std::is_same_v<T, std::uint32_t>)
    return H5T_STD_U32LE;
  else if constexpr (std::is_same_v<T, std::uint16_t>)
    return H5T_STD_U16LE;
  else if constexpr (std::is_same_v<T, std::uint8_t>)
    return H5T_STD_U8LE;
  else if constexpr (std::is_same_v<T, std::int64_t>)
    return H5T_STD_I64LE;
  else if constexpr (std::is_same_v<T, std::int32_t>)
    return H5T_STD_I32LE;
  else if constexpr (std::is_same_v<T, std::int16_t>)
    return H5T_STD_I16LE;
  else if constexpr (std::is_same_v<T, std::int8_t>)
    return H5T_STD_I8LE;
  else
    static_assert(UnsupportedFieldType<T>::value, "particle field element type without an HDF5 mapping");
}
template <class T>
std::string type_description() {
  const std::string bits = std::to_string(8 * sizeof(T)) + "-bit ";
  if constexpr (std::is_floating_point_v<T>)
    return bits + "float";
  else
    return (std::is_signed_v<T> ? "signed " : "unsigned ") + bits + "integer";
}
// True if the stored type holds T exactly (same class, size and signedness; byte order is converted).
template <class T>
bool stored_type_matches(hid_t stored) {
  const H5T_class_t cls = H5Tget_class(stored);
  if (H5Tget_size(stored) != sizeof(T)) return false;
  if constexpr (std::is_floating_point_v<T>) {
    return cls == H5T_FLOAT;
  } else {
    return cls == H5T_INTEGER && H5Tget_sign(stored) == (std::is_signed_v<T> ? H5T_SGN_2 : H5T_SGN_NONE);
  }
}

[[noreturn]] void write_failure(const std::filesystem::path& path, const std::string& what) {
  throw std::runtime_error("cannot write particle file " + path.string() + ": " + what);
}
[[noreturn]] void read_failure(const std::filesystem::path& path, const std::string& what) {
  throw InputError("cannot read particle file " + path.string() + ": " + what);
}

// ---- integrity ------------------------------------------------------------------------------
// The first integrity_block bytes of a particle file are an HDF5 user block (which HDF5 and every HDF5
// tool skip) holding "<integrity_magic><16 hex digits of the hash> <byte count>\n" of the rest of the
// file. A reader checks the length and the hash before HDF5 parses anything, so that a damaged file is an
// error naming it, never a silently different state, and never handed to the HDF5 library (which can
// crash on damaged metadata).

constexpr std::size_t integrity_block = 512;
constexpr std::string_view integrity_magic = "craterkit-integrity-v1 xxh64-like ";
constexpr std::string_view hdf5_signature = "\x89HDF\r\n\x1a\n";

std::uint64_t rotate_left(std::uint64_t x, int r) {
  return (x << r) | (x >> (64 - r));
}

// A 64-bit hash of the bytes of a file from `offset` on, in rounds of the xxHash64 kind (one lane).
struct FileHash {
  std::uint64_t hash = 0;
  std::uint64_t bytes = 0;
};
FileHash hash_file(const std::filesystem::path& path, std::size_t offset) {
  constexpr std::uint64_t p1 = 0x9E3779B185EBCA87ULL, p2 = 0xC2B2AE3D27D4EB4FULL, p3 = 0x165667B19E3779F9ULL;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path.string() + " to check it");
  in.seekg(static_cast<std::streamoff>(offset));
  std::vector<char> buffer(std::size_t{1} << 20);
  std::uint64_t acc = p3, total = 0;
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    const auto n = static_cast<std::size_t>(in.gcount());
    std::size_t i = 0;
    for (; i + 8 <= n; i += 8) {
      std::uint64_t w = 0;
      std::memcpy(&w, buffer.data() + i, 8);
      acc = rotate_left(acc + w * p2, 31) * p1;
    }
    for (; i < n; ++i) acc = rotate_left(acc ^ (static_cast<std::uint8_t>(buffer[i]) * p3), 11) * p1;
    total += n;
  }
  acc ^= total;
  acc ^= acc >> 33;
  acc *= p2;
  acc ^= acc >> 29;
  acc *= p3;
  acc ^= acc >> 32;
  return {acc, total};
}

std::string hex64(std::uint64_t x) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(x));
  return text;
}

}  // namespace

void seal_particle_file(const std::filesystem::path& path) {
  const FileHash h = hash_file(path, integrity_block);
  std::string record = std::string(integrity_magic) + hex64(h.hash) + " " + std::to_string(h.bytes) + "\n";
  record.resize(integrity_block, '\0');
  std::fstream out(path, std::ios::binary | std::ios::in | std::ios::out);
  out.write(record.data(), static_cast<std::streamsize>(record.size()));
  out.flush();
  if (!out) throw std::runtime_error("cannot write the integrity record of " + path.string());
}

namespace {

// Checks a particle file before HDF5 opens it. full: also the hash (else only the record and the length).
void verify_particle_file(const std::filesystem::path& path, bool full) {
  std::ifstream in(path, std::ios::binary);
  if (!in) read_failure(path, "cannot open it");
  std::string head(integrity_block + hdf5_signature.size(), '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  in.close();
  if (head.rfind(hdf5_signature, 0) == 0) return;  // written before files carried a record: not checked
  if (head.rfind(integrity_magic, 0) != 0) {
    read_failure(path, head.size() > integrity_block &&
                               head.compare(integrity_block, hdf5_signature.size(), hdf5_signature) == 0
                           ? "its integrity record is damaged (the file is damaged)"
                           : "not an HDF5 file (or its header is damaged)");
  }
  const std::string record = head.substr(integrity_magic.size(), 64);
  char hash_text[17] = {};
  unsigned long long bytes = 0;
  if (std::sscanf(record.c_str(), "%16[0-9a-f] %llu", hash_text, &bytes) != 2)
    read_failure(path, "its integrity record is damaged (the file is damaged)");
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || size != integrity_block + bytes) {
    read_failure(path, "truncated or damaged: " + std::to_string(size) + " bytes where the file had " +
                           std::to_string(integrity_block + bytes));
  }
  if (!full) return;
  if (hex64(hash_file(path, integrity_block).hash) != hash_text)
    read_failure(path, "its checksum does not match: the file is damaged");
}

// ---- writing --------------------------------------------------------------------------------

template <class T>
void write_scalar_attribute(const std::filesystem::path& path, hid_t object, const std::string& name,
                            T value) {
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attribute(H5Acreate2(object, name.c_str(), file_type<T>(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                   H5Aclose);
  if (!attribute.valid() || H5Awrite(attribute.get(), memory_type<T>(), &value) < 0) {
    write_failure(path, "attribute '" + name + "'");
  }
}

Handle utf8_string_type() {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), H5T_VARIABLE);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  return type;
}

void write_string_attribute(const std::filesystem::path& path, hid_t object, const std::string& name,
                            const std::string& value) {
  Handle type = utf8_string_type();
  Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Handle attribute(H5Acreate2(object, name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                   H5Aclose);
  const char* text = value.c_str();
  if (!attribute.valid() || H5Awrite(attribute.get(), type.get(), &text) < 0) {
    write_failure(path, "attribute '" + name + "'");
  }
}

// A dataset of shape (rows) or (rows, columns) from contiguous data.
template <class T>
void write_dataset(const std::filesystem::path& path, hid_t file, const std::string& name, const T* data,
                   std::size_t rows, std::size_t columns, const std::string& units, int compression = 0) {
  const std::array<hsize_t, 2> dims{rows, columns};
  const int rank = columns == 1 ? 1 : 2;
  Handle space(H5Screate_simple(rank, dims.data(), nullptr), H5Sclose);
  // No modification times in the object headers: the same state gives the same bytes, so files of a
  // resumed and an uninterrupted run can be compared with cmp.
  Handle creation(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  H5Pset_obj_track_times(creation.get(), 0);
  if (compression > 0 && rows > 0) {
    // Deflate needs chunks: whole rows, up to 2^16 particles a chunk.
    const std::array<hsize_t, 2> chunk{std::min<hsize_t>(rows, 65536), columns};
    if (H5Pset_chunk(creation.get(), rank, chunk.data()) < 0 ||
        H5Pset_deflate(creation.get(), static_cast<unsigned>(compression)) < 0) {
      write_failure(path, "cannot set up compression of dataset '" + name + "'");
    }
  }
  Handle dataset(
      H5Dcreate2(file, name.c_str(), file_type<T>(), space.get(), H5P_DEFAULT, creation.get(), H5P_DEFAULT),
      H5Dclose);
  if (!dataset.valid()) write_failure(path, "cannot create dataset '" + name + "'");
  if (rows > 0 && H5Dwrite(dataset.get(), memory_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
    write_failure(path, "cannot write dataset '" + name + "'");
  }
  if (!units.empty()) write_string_attribute(path, dataset.get(), "units", units);
}

const std::array<const char*, 6> reserved_attributes{"format",         "kind", "format_version",
                                                     "particle_count", "time", "step"};

void check_attribute_names(const RunAttributes& attributes) {
  auto check = [&](const std::string& name) {
    if (name.empty()) throw std::invalid_argument("run attribute with an empty name");
    for (const char* reserved : reserved_attributes) {
      if (name == reserved) {
        throw std::invalid_argument("run attribute name '" + name +
                                    "' is reserved by the particle file format");
      }
    }
  };
  for (const auto& [name, value] : attributes.numbers) {
    check(name);
    if (attributes.texts.count(name) != 0) {
      throw std::invalid_argument("run attribute '" + name + "' is both a number and a text");
    }
  }
  for (const auto& [name, value] : attributes.texts) check(name);
}

// ---- reading --------------------------------------------------------------------------------

std::string read_string_attribute(hid_t attribute) {
  Handle stored(H5Aget_type(attribute), H5Tclose);
  if (H5Tis_variable_str(stored.get()) > 0) {
    Handle type = utf8_string_type();
    char* text = nullptr;
    if (H5Aread(attribute, type.get(), &text) < 0) return {};
    std::string value = text != nullptr ? text : "";
    H5free_memory(text);
    return value;
  }
  // Fixed-length string (written by other tools): read the bytes, drop padding.
  const std::size_t size = H5Tget_size(stored.get());
  std::string value(size, '\0');
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), size);
  if (H5Aread(attribute, type.get(), value.data()) < 0) return {};
  value.resize(value.find_first_of('\0') == std::string::npos ? size : value.find_first_of('\0'));
  while (!value.empty() && value.back() == ' ') value.pop_back();
  return value;
}

struct AttributeScan {
  std::map<std::string, double> numbers;
  std::map<std::string, std::string> texts;
  std::map<std::string, std::uint64_t> integers;  // reserved integer attributes
};

herr_t collect_attribute(hid_t object, const char* name, const H5A_info_t*, void* data) {
  auto& scan = *static_cast<AttributeScan*>(data);
  Handle attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
  if (!attribute.valid()) return -1;
  Handle type(H5Aget_type(attribute.get()), H5Tclose);
  Handle space(H5Aget_space(attribute.get()), H5Sclose);
  if (H5Sget_simple_extent_npoints(space.get()) != 1) return 0;  // arrays: not ours, skip
  switch (H5Tget_class(type.get())) {
    case H5T_STRING:
      scan.texts[name] = read_string_attribute(attribute.get());
      break;
    case H5T_FLOAT: {
      double value = 0;
      if (H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value) < 0) return -1;
      scan.numbers[name] = value;
      break;
    }
    case H5T_INTEGER: {
      std::uint64_t value = 0;
      if (H5Aread(attribute.get(), H5T_NATIVE_UINT64, &value) < 0) return -1;
      scan.integers[name] = value;
      break;
    }
    default:
      break;
  }
  return 0;
}

// full_check: verify the whole file's hash (else only its integrity record and length).
Handle open_particle_file(const std::filesystem::path& path, AttributeScan& scan, bool full_check) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) read_failure(path, "no such file");
  if (!std::filesystem::is_regular_file(path, ec)) read_failure(path, "not a regular file");
  verify_particle_file(path, full_check);
  if (H5Fis_hdf5(path.c_str()) <= 0) read_failure(path, "not an HDF5 file (or its header is corrupt)");
  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG);
  Handle file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, fapl.get()), H5Fclose);
  if (!file.valid()) read_failure(path, "HDF5 cannot open it (truncated or corrupt file?)");
  if (H5Aiterate2(file.get(), H5_INDEX_NAME, H5_ITER_INC, nullptr, collect_attribute, &scan) < 0) {
    read_failure(path, "cannot read its attributes (corrupt file?)");
  }
  const auto format = scan.texts.find("format");
  if (format == scan.texts.end() || format->second != particle_file_format) {
    read_failure(path, std::string("not a craterkit particle file (root attribute 'format' is not '") +
                           particle_file_format + "')");
  }
  const auto version = scan.integers.find("format_version");
  if (version == scan.integers.end() ||
      version->second != static_cast<std::uint64_t>(particle_file_version)) {
    read_failure(path, "unsupported format_version (this craterkit reads version " +
                           std::to_string(particle_file_version) + ")");
  }
  for (const char* required : {"particle_count", "step"}) {
    if (scan.integers.count(required) == 0)
      read_failure(path, std::string("root attribute '") + required + "' is missing");
  }
  if (scan.numbers.count("time") == 0) read_failure(path, "root attribute 'time' is missing");
  if (scan.texts.count("kind") == 0) read_failure(path, "root attribute 'kind' is missing");
  return file;
}

// A particle file holds the solid-mechanics group exactly when it holds this dataset.
constexpr const char* solid_marker_field = "stress_xx";

template <class T>
void read_field(const std::filesystem::path& path, hid_t file, std::string_view field_name,
                std::vector<T>& field, std::uint64_t count) {
  const std::string name(field_name);
  if (H5Lexists(file, name.c_str(), H5P_DEFAULT) <= 0)
    read_failure(path, "dataset '" + name + "' is missing");
  Handle dataset(H5Dopen2(file, name.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dataset.valid()) read_failure(path, "'" + name + "' is not a dataset");
  Handle space(H5Dget_space(dataset.get()), H5Sclose);
  hsize_t length = 0;
  if (H5Sget_simple_extent_ndims(space.get()) != 1 ||
      H5Sget_simple_extent_dims(space.get(), &length, nullptr) != 1) {
    read_failure(path, "dataset '" + name + "' is not one-dimensional");
  }
  if (length != count) {
    read_failure(path, "dataset '" + name + "' has " + std::to_string(length) +
                           " entries, particle_count is " + std::to_string(count));
  }
  Handle stored(H5Dget_type(dataset.get()), H5Tclose);
  if (!stored_type_matches<T>(stored.get())) {
    read_failure(path, "dataset '" + name + "' does not hold " + type_description<T>() + "s");
  }
  field.resize(count);
  if (count > 0 &&
      H5Dread(dataset.get(), memory_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, field.data()) < 0) {
    read_failure(path, "dataset '" + name + "' cannot be read (truncated or corrupt file?)");
  }
}

// HDF5 closes the files it still knows of when the program exits; a file whose close failed (a full disk)
// crashes the HDF5 1.10 library there. Every file here is closed explicitly, so that clean-up is not needed.
const bool hdf5_clean_up_at_exit_disabled = [] {
  H5dont_atexit();
  return true;
}();

// A full disk found before HDF5 writes anything: the size of the file to be written (the fields, the
// visualisation copies, a margin for the metadata) against the free space of its folder.
void require_free_space(const std::filesystem::path& path, const Particles& particles,
                        const ParticleFileOptions& options) {
  std::uintmax_t bytes = 64u << 10;
  particles.for_each_field(
      [&](std::string_view, const auto& field) { bytes += field.size() * sizeof(field[0]); });
  if (options.visualisation_vectors)
    bytes += particles.size() * (2 * 3 * sizeof(double) + sizeof(std::int64_t));
  std::error_code ec;
  const auto parent = path.parent_path().empty() ? std::filesystem::path(".") : path.parent_path();
  const auto space = std::filesystem::space(parent, ec);
  if (!ec && space.available < bytes) {
    write_failure(path, "the disk is full: " + std::to_string(space.available) + " bytes free in " +
                            parent.string() + ", about " + std::to_string(bytes) + " needed");
  }
}

}  // namespace

void sync_to_disk(const std::filesystem::path& file) {
  const int fd = ::open(file.c_str(), O_RDONLY);
  if (fd < 0) throw std::runtime_error("cannot open " + file.string() + " to flush it to disk");
  const int status = ::fsync(fd);
  ::close(fd);
  if (status != 0) throw std::runtime_error("cannot flush " + file.string() + " to disk");
}

void sync_directory(const std::filesystem::path& directory) noexcept {
  const int fd = ::open(directory.empty() ? "." : directory.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) return;
  static_cast<void>(::fsync(fd));
  ::close(fd);
}

void write_particle_file(const std::filesystem::path& path, const Particles& particles,
                         const RunAttributes& attributes, const ParticleFileOptions& options) {
  check_attribute_names(attributes);
  const SilenceHdf5Errors silence;
  const std::size_t n = particles.size();
  require_free_space(path, particles, options);

  Handle fapl(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG);
  Handle fcpl(H5Pcreate(H5P_FILE_CREATE), H5Pclose);
  H5Pset_obj_track_times(fcpl.get(), 0);  // root group without modification times (see write_dataset)
  if (options.integrity_record)
    H5Pset_userblock(fcpl.get(), integrity_block);  // room for the integrity record (seal_particle_file)
  Handle file(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, fcpl.get(), fapl.get()), H5Fclose);
  if (!file.valid())
    write_failure(path, "cannot create the file (does the directory exist and is it writable?)");

  write_string_attribute(path, file.get(), "format", particle_file_format);
  write_string_attribute(path, file.get(), "kind", options.kind);
  write_scalar_attribute<std::int32_t>(path, file.get(), "format_version", particle_file_version);
  write_scalar_attribute<std::uint64_t>(path, file.get(), "particle_count", n);
  write_scalar_attribute<double>(path, file.get(), "time", attributes.time);
  write_scalar_attribute<std::uint64_t>(path, file.get(), "step", attributes.step);
  for (const auto& [name, value] : attributes.numbers)
    write_scalar_attribute<double>(path, file.get(), name, value);
  for (const auto& [name, value] : attributes.texts) write_string_attribute(path, file.get(), name, value);

  particles.for_each_field([&](std::string_view name, const auto& field) {
    using T = typename std::decay_t<decltype(field)>::value_type;
    if (field.size() != n) {
      throw std::invalid_argument("particle field '" + std::string(name) + "' has " +
                                  std::to_string(field.size()) + " entries but x has " + std::to_string(n));
    }
    write_dataset<T>(path, file.get(), std::string(name), field.data(), n, 1, field_unit(name),
                     options.compression);
  });

  if (options.visualisation_vectors) {
    // Interleaved copies for the XDMF geometry and velocity vector (readers of the fields ignore them).
    std::vector<double> interleaved(3 * n);
    auto write_vector = [&](const char* name, const std::vector<double>& a, const std::vector<double>& b,
                            const std::vector<double>& c, const char* units) {
      for (std::size_t i = 0; i < n; ++i) {
        interleaved[3 * i] = a[i];
        interleaved[3 * i + 1] = b[i];
        interleaved[3 * i + 2] = c[i];
      }
      write_dataset<double>(path, file.get(), name, interleaved.data(), n, 3, units, options.compression);
    };
    write_vector("position", particles.x, particles.y, particles.z, "m");
    write_vector("velocity", particles.vx, particles.vy, particles.vz, "m/s");
    if (particles.solid_fields) {
      // The Cauchy stress sigma = S - P I as an XDMF Tensor6 (xx, xy, xz, yy, yz, zz), S traceless.
      std::vector<double> stress(6 * n);
      for (std::size_t i = 0; i < n; ++i) {
        const double p = particles.pressure[i];
        stress[6 * i] = particles.stress_xx[i] - p;
        stress[6 * i + 1] = particles.stress_xy[i];
        stress[6 * i + 2] = particles.stress_xz[i];
        stress[6 * i + 3] = particles.stress_yy[i] - p;
        stress[6 * i + 4] = particles.stress_yz[i];
        stress[6 * i + 5] = -particles.stress_xx[i] - particles.stress_yy[i] - p;
      }
      write_dataset<double>(path, file.get(), "stress", stress.data(), n, 6, "Pa", options.compression);
    }
    // Explicit Polyvertex connectivity 0..n-1: ParaView's Xdmf3 readers make no vertex cells without
    // it (its XDMF 2 reader does), and filters that work on cells then see nothing.
    std::vector<std::int64_t> connectivity(n);
    for (std::size_t i = 0; i < n; ++i) connectivity[i] = static_cast<std::int64_t>(i);
    write_dataset<std::int64_t>(path, file.get(), "connectivity", connectivity.data(), n, 1, "",
                                options.compression);
  }

  if (H5Fflush(file.get(), H5F_SCOPE_GLOBAL) < 0 || !file.close())
    write_failure(path, "cannot flush and close it");
  if (options.integrity_record) seal_particle_file(path);
  sync_to_disk(path);
}

ParticleFileHeader read_particle_file_header(const std::filesystem::path& path) {
  const SilenceHdf5Errors silence;
  AttributeScan scan;
  Handle file = open_particle_file(path, scan, /*full_check=*/false);
  return {scan.texts["kind"], scan.numbers["time"], scan.integers["step"], scan.integers["particle_count"],
          H5Lexists(file.get(), solid_marker_field, H5P_DEFAULT) > 0};
}

Particles read_particle_file(const std::filesystem::path& path, RunAttributes* attributes) {
  const SilenceHdf5Errors silence;
  AttributeScan scan;
  Handle file = open_particle_file(path, scan, /*full_check=*/true);
  const std::uint64_t count = scan.integers["particle_count"];

  Particles particles;
  particles.solid_fields = H5Lexists(file.get(), solid_marker_field, H5P_DEFAULT) > 0;
  particles.for_each_field([&](std::string_view name, auto& field) {
    // Fields added after a file was written (Particles::default_for_absent_field) take their default.
    const auto fallback = Particles::default_for_absent_field(name);
    if (fallback && H5Lexists(file.get(), std::string(name).c_str(), H5P_DEFAULT) <= 0) {
      field.assign(count, static_cast<typename std::decay_t<decltype(field)>::value_type>(*fallback));
      return;
    }
    read_field(path, file.get(), name, field, count);
  });

  if (attributes != nullptr) {
    attributes->time = scan.numbers["time"];
    attributes->step = scan.integers["step"];
    attributes->numbers.clear();
    attributes->texts.clear();
    for (const auto& [name, value] : scan.numbers) {
      if (name != "time") attributes->numbers[name] = value;
    }
    for (const auto& [name, value] : scan.texts) {
      if (name != "format" && name != "kind") attributes->texts[name] = value;
    }
    // Integer attributes other than the reserved ones come from other tools: keep them as numbers.
    for (const auto& [name, value] : scan.integers) {
      if (name != "particle_count" && name != "step" && name != "format_version") {
        attributes->numbers[name] = static_cast<double>(value);
      }
    }
  }
  return particles;
}

}  // namespace craterkit::sph::detail
