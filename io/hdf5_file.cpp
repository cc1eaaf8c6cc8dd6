#include "io/hdf5_file.h"

#include "io/safe_write.h"

#include <algorithm>
#include <cstdint>
#include <mutex>
#include <stdexcept>

namespace tessera::h5 {

namespace {

// HDF5 prints its own error stack by default; we report errors ourselves. Nor may it close
// files in its exit handler: a file whose close failed (a full disk) would be flushed again after
// main() returned, and crash there (H5dont_atexit must come before any other HDF5 call).
void initializeLibrary() {
  static std::once_flag once;
  std::call_once(once, [] {
    H5dont_atexit();
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  });
}

hid_t check(hid_t id, const std::string& what) {
  if (id < 0) throw std::runtime_error("HDF5: cannot " + what);
  return id;
}

void check(herr_t status, const std::string& what) {
  if (status < 0) throw std::runtime_error("HDF5: cannot " + what);
}

template <class T>
hid_t nativeType();
template <>
hid_t nativeType<double>() { return H5T_NATIVE_DOUBLE; }
template <>
hid_t nativeType<float>() { return H5T_NATIVE_FLOAT; }
template <>
hid_t nativeType<std::int32_t>() { return H5T_NATIVE_INT32; }
template <>
hid_t nativeType<std::uint8_t>() { return H5T_NATIVE_UINT8; }

// The element count of a dataset, refused when it claims more data than the file can hold: at
// most the bytes stored times deflate's largest ratio (1032:1, RFC 1951), plus 1 MB of fill
// values. A damaged file then fails here instead of allocating (and touching) terabytes.
hsize_t checkedCount(hid_t set, const std::vector<hsize_t>& shape, std::size_t elementBytes, const std::string& name) {
  double count = 1;
  for (hsize_t d : shape) count *= static_cast<double>(d);
  const double stored = static_cast<double>(H5Dget_storage_size(set));
  if (count * static_cast<double>(elementBytes) > 1032.0 * stored + 1e6)
    throw std::runtime_error("HDF5: dataset '" + name + "' claims " + std::to_string(static_cast<long long>(count)) +
                             " elements, more than the file holds");
  return static_cast<hsize_t>(count);
}

}  // namespace

Handle& Handle::operator=(Handle&& other) noexcept {
  if (this != &other) {
    this->~Handle();
    id_ = other.id_;
    other.id_ = H5I_INVALID_HID;
  }
  return *this;
}

Handle::~Handle() {
  if (id_ >= 0) H5Idec_ref(id_);
}

// Files are written in the HDF5 1.10 format, whose metadata (superblock, object headers, heaps,
// and the chunk indexes of arrays) carries checksums: a damaged file is then refused by the
// library when it is opened or an object read, instead of being parsed (the 1.6 format has no
// checksums, and a damaged object header could crash the library; 1.8's chunk index, a B-tree,
// has none, and a flipped bit in it changed values read).
Handle createFile(const std::string& path) {
  initializeLibrary();
  Handle access(check(H5Pcreate(H5P_FILE_ACCESS), "make file properties"));
  check(H5Pset_libver_bounds(access.get(), H5F_LIBVER_V110, H5F_LIBVER_LATEST), "choose the file format");
  return Handle(check(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get()), "create " + path));
}

Handle openFileReadOnly(const std::string& path) {
  initializeLibrary();
  return Handle(check(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open " + path + " as HDF5"));
}

void writeFile(const std::filesystem::path& target, const std::function<void(hid_t file)>& write) {
  FileSetWriter file;
  addFile(file, target, write);
  file.commit();
}

void addFile(FileSetWriter& files, const std::filesystem::path& target, const std::function<void(hid_t file)>& write) {
  files.add(
      target,
      [&](const std::filesystem::path& temporary) {
        Handle file = createFile(temporary.string());
        write(file.get());  // the objects it opened are closed when it returns
        const hid_t id = file.release();  // the handle's destructor would close without checking
        if (H5Fclose(id) < 0) throw std::runtime_error("HDF5: cannot flush and close the file");
      },
      [](const std::filesystem::path& temporary) { openFileReadOnly(temporary.string()); });
}

Handle createGroup(hid_t parent, const std::string& name) {
  return Handle(check(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), "create group " + name));
}

Handle openGroup(hid_t parent, const std::string& name) {
  return Handle(check(H5Gopen2(parent, name.c_str(), H5P_DEFAULT), "open group '" + name + "'"));
}

std::vector<std::string> childNames(hid_t group) {
  H5G_info_t info;
  check(H5Gget_info(group, &info), "list group");
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t size = H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    check(static_cast<hid_t>(size), "list group");
    std::string name(static_cast<std::size_t>(size), '\0');
    H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), size + 1, H5P_DEFAULT);
    names.push_back(name);
  }
  return names;
}

namespace {
// Every dataset with data is chunked and checksummed (Fletcher-32: HDF5 checks it on every read,
// so a damaged chunk fails to read instead of changing an answer; the 1.10 format checksums the
// metadata), large ones (grids) also compressed, in chunks of at most 2^16 elements.
Handle checksummedProperties(const std::vector<hsize_t>& dims, hsize_t count, const std::string& name) {
  Handle properties(check(H5Pcreate(H5P_DATASET_CREATE), "make dataset properties"));
  if (count == 0) return properties;
  constexpr hsize_t kChunkElements = 1 << 16;
  std::vector<hsize_t> chunk(dims);
  hsize_t total = count;
  for (std::size_t a = 0; a < chunk.size() && total > kChunkElements; ++a) {
    const hsize_t rest = total / chunk[a];
    chunk[a] = std::max<hsize_t>(1, kChunkElements / rest);
    total = chunk[a] * rest;
  }
  check(H5Pset_chunk(properties.get(), static_cast<int>(chunk.size()), chunk.data()), "chunk " + name);
  check(H5Pset_fletcher32(properties.get()), "checksum " + name);
  if (count >= 4096) check(H5Pset_deflate(properties.get(), 4), "compress " + name);
  return properties;
}
}  // namespace

template <class T>
void writeDataset(hid_t parent, const std::string& name, const std::vector<T>& data, const std::vector<hsize_t>& dims) {
  hsize_t count = 1;
  for (hsize_t d : dims) count *= d;
  if (count != data.size()) throw std::logic_error("writeDataset " + name + ": size does not match dims");
  Handle space(check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), "make dataspace"));
  Handle properties = checksummedProperties(dims, count, name);
  Handle set(check(H5Dcreate2(parent, name.c_str(), nativeType<T>(), space.get(), H5P_DEFAULT, properties.get(),
                              H5P_DEFAULT),
                   "create dataset " + name));
  if (count > 0) check(H5Dwrite(set.get(), nativeType<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()), "write " + name);
}

template <class T>
std::vector<T> readDataset(hid_t parent, const std::string& name, std::vector<hsize_t>* dims) {
  Handle set(check(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), "open dataset '" + name + "'"));
  Handle type(check(H5Dget_type(set.get()), "read type of " + name));
  if (H5Tget_class(type.get()) != H5Tget_class(nativeType<T>()))  // HDF5 would convert 2.5 to 2 without a word
    throw std::runtime_error("HDF5: dataset '" + name + "' holds another kind of number than expected");
  Handle space(check(H5Dget_space(set.get()), "read shape of " + name));
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) throw std::runtime_error("HDF5: cannot read rank of " + name);
  std::vector<hsize_t> shape(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.get(), shape.data(), nullptr);
  const hsize_t count = checkedCount(set.get(), shape, sizeof(T), name);
  std::vector<T> data(count);
  if (count > 0) check(H5Dread(set.get(), nativeType<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data.data()), "read " + name);
  if (dims) *dims = shape;
  return data;
}

#define TESSERA_H5_INSTANTIATE(T)                                                                          \
  template void writeDataset<T>(hid_t, const std::string&, const std::vector<T>&, const std::vector<hsize_t>&); \
  template std::vector<T> readDataset<T>(hid_t, const std::string&, std::vector<hsize_t>*);
TESSERA_H5_INSTANTIATE(double)
TESSERA_H5_INSTANTIATE(float)
TESSERA_H5_INSTANTIATE(std::int32_t)
TESSERA_H5_INSTANTIATE(std::uint8_t)
#undef TESSERA_H5_INSTANTIATE

namespace {
void writeScalarAttribute(hid_t object, const std::string& name, hid_t type, const void* value) {
  Handle space(check(H5Screate(H5S_SCALAR), "make dataspace"));
  Handle attribute(check(H5Acreate2(object, name.c_str(), type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                         "create attribute " + name));
  check(H5Awrite(attribute.get(), type, value), "write attribute " + name);
}

Handle openAttribute(hid_t object, const std::string& name) {
  return Handle(check(H5Aopen(object, name.c_str(), H5P_DEFAULT), "read attribute '" + name + "'"));
}
}  // namespace

namespace {
Handle fixedStringType(std::size_t size) {
  Handle type(check(H5Tcopy(H5T_C_S1), "make string type"));
  check(H5Tset_size(type.get(), std::max<std::size_t>(1, size)), "size string type");
  check(H5Tset_strpad(type.get(), H5T_STR_NULLPAD), "pad string type");
  return type;
}

std::string trimNulls(std::string value) {
  const auto end = value.find('\0');
  if (end != std::string::npos) value.resize(end);
  return value;
}
}  // namespace

void writeStrings(hid_t parent, const std::string& name, const std::vector<std::string>& values) {
  std::size_t width = 1;
  for (const auto& v : values) width = std::max(width, v.size());
  std::string packed(width * values.size(), '\0');
  for (std::size_t i = 0; i < values.size(); ++i) packed.replace(i * width, values[i].size(), values[i]);
  Handle type = fixedStringType(width);
  const hsize_t count = values.size();
  Handle space(check(H5Screate_simple(1, &count, nullptr), "make dataspace"));
  Handle properties = checksummedProperties({count}, count, name);
  Handle set(check(H5Dcreate2(parent, name.c_str(), type.get(), space.get(), H5P_DEFAULT, properties.get(), H5P_DEFAULT),
                   "create dataset " + name));
  if (count > 0) check(H5Dwrite(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, packed.data()), "write " + name);
}

std::vector<std::string> readStrings(hid_t parent, const std::string& name) {
  Handle set(check(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), "open dataset '" + name + "'"));
  Handle type(check(H5Dget_type(set.get()), "read type of " + name));
  if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0)
    throw std::runtime_error("HDF5: dataset '" + name + "' is not a fixed-length string array");
  Handle space(check(H5Dget_space(set.get()), "read shape of " + name));
  hsize_t count = 0;
  if (H5Sget_simple_extent_ndims(space.get()) != 1) throw std::runtime_error("HDF5: dataset '" + name + "' is not 1-D");
  H5Sget_simple_extent_dims(space.get(), &count, nullptr);
  const std::size_t width = H5Tget_size(type.get());
  if (width == 0) throw std::runtime_error("HDF5: cannot read the string width of " + name);
  checkedCount(set.get(), {count}, width, name);
  std::string packed(width * count, '\0');
  if (count > 0) check(H5Dread(set.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, packed.data()), "read " + name);
  std::vector<std::string> values;
  for (hsize_t i = 0; i < count; ++i) values.push_back(trimNulls(packed.substr(i * width, width)));
  return values;
}

void writeAttribute(hid_t object, const std::string& name, const std::string& value) {
  Handle type = fixedStringType(value.size());
  writeScalarAttribute(object, name, type.get(), value.empty() ? "" : value.data());
}

void writeDatasetAttribute(hid_t parent, const std::string& dataset, const std::string& name, const std::string& value) {
  Handle d(H5Dopen2(parent, dataset.c_str(), H5P_DEFAULT));
  if (d.get() < 0) throw std::runtime_error("HDF5: no dataset '" + dataset + "' for its attribute '" + name + "'");
  writeAttribute(d.get(), name, value);
}

void writeAttribute(hid_t object, const std::string& name, double value) {
  writeScalarAttribute(object, name, H5T_NATIVE_DOUBLE, &value);
}

void writeAttribute(hid_t object, const std::string& name, std::int64_t value) {
  writeScalarAttribute(object, name, H5T_NATIVE_INT64, &value);
}

std::string readStringAttribute(hid_t object, const std::string& name) {
  Handle attribute = openAttribute(object, name);
  Handle type(check(H5Aget_type(attribute.get()), "read type of " + name));
  if (H5Tget_class(type.get()) != H5T_STRING) throw std::runtime_error("HDF5: attribute '" + name + "' is not a string");
  if (H5Tis_variable_str(type.get()) > 0) throw std::runtime_error("HDF5: attribute '" + name + "' is a variable-length string");
  const std::size_t size = H5Tget_size(type.get());
  std::string value(size, '\0');
  check(H5Aread(attribute.get(), type.get(), value.data()), "read attribute " + name);
  return trimNulls(value);
}

double readDoubleAttribute(hid_t object, const std::string& name) {
  Handle attribute = openAttribute(object, name);
  double value = 0;
  check(H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value), "read attribute " + name);
  return value;
}

double readDoubleAttribute(hid_t object, const std::string& name, double absent) {
  const htri_t exists = H5Aexists(object, name.c_str());
  check(exists, "look for attribute " + name);
  return exists > 0 ? readDoubleAttribute(object, name) : absent;
}

std::int64_t readIntAttribute(hid_t object, const std::string& name) {
  Handle attribute = openAttribute(object, name);
  Handle type(check(H5Aget_type(attribute.get()), "read type of " + name));
  if (H5Tget_class(type.get()) != H5T_INTEGER)  // HDF5 would convert 2.5 to 2 without a word
    throw std::runtime_error("HDF5: attribute '" + name + "' is not an integer");
  std::int64_t value = 0;
  check(H5Aread(attribute.get(), H5T_NATIVE_INT64, &value), "read attribute " + name);
  return value;
}

}  // namespace tessera::h5
