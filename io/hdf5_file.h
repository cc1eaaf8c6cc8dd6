#pragma once
#include "io/safe_write.h"

#include <hdf5.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace tessera::h5 {

/// Owns one HDF5 identifier (file, group, dataset, dataspace, attribute, datatype).
class Handle {
public:
  Handle() = default;
  explicit Handle(hid_t id) : id_(id) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept : id_(other.id_) { other.id_ = H5I_INVALID_HID; }
  Handle& operator=(Handle&& other) noexcept;
  ~Handle();
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  /// Gives up ownership: the caller closes the identifier.
  hid_t release() {
    const hid_t id = id_;
    id_ = H5I_INVALID_HID;
    return id;
  }

private:
  hid_t id_ = H5I_INVALID_HID;
};

/// Errors from these helpers are std::runtime_error with the object path; callers that read
/// user files turn them into InputError naming the file.
Handle createFile(const std::string& path);
Handle openFileReadOnly(const std::string& path);
/// Writes an HDF5 file whole or not at all (writeFileSafely): creates it under a temporary name,
/// lets `write` fill the open file, closes it checking the flush (a full disk shows up there), and
/// reopens it (the library checks its end-of-file address) before the rename. Throws WriteError.
void writeFile(const std::filesystem::path& target, const std::function<void(hid_t file)>& write);
/// The same, as one file of a set written together (FileSetWriter: renamed at its commit).
void addFile(FileSetWriter& files, const std::filesystem::path& target, const std::function<void(hid_t file)>& write);
Handle createGroup(hid_t parent, const std::string& name);
Handle openGroup(hid_t parent, const std::string& name);
std::vector<std::string> childNames(hid_t group);

template <class T>
void writeDataset(hid_t parent, const std::string& name, const std::vector<T>& data, const std::vector<hsize_t>& dims);
/// Reads a whole dataset; `dims` receives its shape. Throws if the element count is off.
template <class T>
std::vector<T> readDataset(hid_t parent, const std::string& name, std::vector<hsize_t>* dims = nullptr);

/// A 1-D dataset of fixed-length strings (length of the longest, at least 1).
void writeStrings(hid_t parent, const std::string& name, const std::vector<std::string>& values);
std::vector<std::string> readStrings(hid_t parent, const std::string& name);

void writeAttribute(hid_t object, const std::string& name, const std::string& value);
/// The string attribute `name` = `value` on the dataset `dataset` of `parent` (e.g. its "unit").
void writeDatasetAttribute(hid_t parent, const std::string& dataset, const std::string& name, const std::string& value);
void writeAttribute(hid_t object, const std::string& name, double value);
void writeAttribute(hid_t object, const std::string& name, std::int64_t value);
std::string readStringAttribute(hid_t object, const std::string& name);
double readDoubleAttribute(hid_t object, const std::string& name);
/// The attribute's value, or `absent` when the object has no attribute of that name.
double readDoubleAttribute(hid_t object, const std::string& name, double absent);
std::int64_t readIntAttribute(hid_t object, const std::string& name);

}  // namespace tessera::h5
