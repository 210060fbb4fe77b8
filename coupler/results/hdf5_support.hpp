#pragma once
// Small helpers over the HDF5 C API shared by the results file and the coupled-solver state
// file: RAII handles, errors as exceptions carrying HDF5's innermost message, attributes.
#include <hdf5.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace cocopp {

/// Owns one HDF5 identifier and releases it with the matching H5?close function.
class H5Handle {
 public:
  using Closer = herr_t (*)(hid_t);

  H5Handle() = default;
  H5Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  H5Handle(H5Handle&& other) noexcept { *this = std::move(other); }
  H5Handle& operator=(H5Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = other.id_;
      closer_ = other.closer_;
      other.id_ = H5I_INVALID_HID;
    }
    return *this;
  }
  H5Handle(const H5Handle&) = delete;
  H5Handle& operator=(const H5Handle&) = delete;
  ~H5Handle() { reset(); }

  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  /// Closes now; returns the closer's status (0 if there was nothing to close).
  herr_t reset() {
    herr_t status = 0;
    if (valid() && closer_) status = closer_(id_);
    id_ = H5I_INVALID_HID;
    return status;
  }

 private:
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

namespace hdf5 {

/// An HDF5 call failed; the public methods add the file name.
class H5Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// HDF5 prints its error stack to stderr by default. The writer reports failures as exceptions
// that carry the innermost HDF5 message instead, so printing is off while it works.
class QuietErrors {
 public:
  QuietErrors() {
    H5Eget_auto2(H5E_DEFAULT, &function_, &data_);
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
  ~QuietErrors() { H5Eset_auto2(H5E_DEFAULT, function_, data_); }
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;

 private:
  H5E_auto2_t function_ = nullptr;
  void* data_ = nullptr;
};

/// The most specific message on the HDF5 error stack (e.g. the errno text of a failed open).
std::string hdf5_error();

/// Returns `id` (or status) unless it signals an HDF5 failure.
template <typename Id>
Id checked(Id id, const std::string& what) {
  if (id < 0) throw H5Error(what + " failed: " + hdf5_error());
  return id;
}

std::string valid_utf8(const std::string& text);

H5Handle string_type();

/// The enum h5py reads as numpy bool.
H5Handle bool_type();

H5Handle dataspace(const std::vector<hsize_t>& dims, const hsize_t* max_dims = nullptr);

/// Creates (or replaces: statuses are rewritten at close) attribute `name` and writes `data`;
/// dims {} makes a scalar attribute.
void set_attribute(hid_t object, const std::string& name, hid_t file_type, hid_t memory_type,
                   const std::vector<hsize_t>& dims, const void* data);

void set_string(hid_t object, const std::string& name, const std::string& value);

void set_strings(hid_t object, const std::string& name, const std::vector<std::string>& values);

void set_double(hid_t object, const std::string& name, double value);

void set_int(hid_t object, const std::string& name, std::int64_t value);

void set_ints(hid_t object, const std::string& name, const std::vector<std::int64_t>& values);

H5Handle create_group(hid_t parent, const std::string& name);

/// A dataset of fixed shape, written once (model part ids and coordinates).
void write_fixed(hid_t parent, const std::string& name, hid_t file_type, hid_t memory_type,
                 const std::vector<hsize_t>& dims, const void* data, const char* unit);

std::string object_name(hid_t object);

// Reading (ResultsReader, the state file). Each call is checked and throws H5Error.

/// The names of the links in a group, in name order.
std::vector<std::string> member_names(hid_t group);

std::vector<hsize_t> dataset_shape(hid_t dataset);

std::size_t element_count(hid_t dataset);

/// All values of a numeric dataset in C order, converted to double.
std::vector<double> read_doubles(hid_t dataset);

/// A numeric attribute (scalar or array) of `object` (a path from `location`), as doubles.
std::vector<double> read_doubles_attribute(hid_t location, const std::string& object,
                                           const std::string& name);

/// A string attribute (scalar or array) of `object` (a path from `location`).
std::vector<std::string> read_strings_attribute(hid_t location, const std::string& object,
                                                const std::string& name);

}  // namespace hdf5
}  // namespace cocopp
