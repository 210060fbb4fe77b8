#include "coupler/results/hdf5_support.hpp"

#include <algorithm>
#include <nlohmann/json.hpp>

namespace cocopp::hdf5 {

namespace {

herr_t keep_innermost(unsigned n, const H5E_error2_t* error, void* out) {
  if (n == 0 && error->desc) *static_cast<std::string*>(out) = error->desc;
  return 0;
}

}  // namespace

/// The most specific message on the HDF5 error stack (e.g. the errno text of a failed open).
std::string hdf5_error() {
  std::string detail;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, keep_innermost, &detail);
  return detail.empty() ? "unknown HDF5 error" : detail;
}

// Attributes are declared UTF-8 (so h5py returns str, not bytes); messages may quote solver
// output with arbitrary bytes, which would make reading them fail. Invalid bytes become U+FFFD.
std::string valid_utf8(const std::string& text) {
  using nlohmann::json;
  return json::parse(json(text).dump(-1, ' ', false, json::error_handler_t::replace))
      .get<std::string>();
}

H5Handle string_type() {
  H5Handle type(checked(H5Tcopy(H5T_C_S1), "H5Tcopy"), H5Tclose);
  checked(H5Tset_size(type.get(), H5T_VARIABLE), "H5Tset_size");
  checked(H5Tset_cset(type.get(), H5T_CSET_UTF8), "H5Tset_cset");
  return type;
}

/// The enum h5py reads as numpy bool.
H5Handle bool_type() {
  H5Handle type(checked(H5Tenum_create(H5T_NATIVE_INT8), "H5Tenum_create"), H5Tclose);
  const std::int8_t no = 0, yes = 1;
  checked(H5Tenum_insert(type.get(), "FALSE", &no), "H5Tenum_insert");
  checked(H5Tenum_insert(type.get(), "TRUE", &yes), "H5Tenum_insert");
  return type;
}

H5Handle dataspace(const std::vector<hsize_t>& dims, const hsize_t* max_dims) {
  const int rank = static_cast<int>(dims.size());
  return {checked(rank == 0 ? H5Screate(H5S_SCALAR) : H5Screate_simple(rank, dims.data(), max_dims),
                  "H5Screate"),
          H5Sclose};
}

/// Creates (or replaces: statuses are rewritten at close) attribute `name` and writes `data`;
/// dims {} makes a scalar attribute.
void set_attribute(hid_t object, const std::string& name, hid_t file_type, hid_t memory_type,
                   const std::vector<hsize_t>& dims, const void* data) {
  if (checked(H5Aexists(object, name.c_str()), "H5Aexists " + name) > 0)
    checked(H5Adelete(object, name.c_str()), "deleting attribute " + name);
  const H5Handle space = dataspace(dims);
  const H5Handle attribute(
      checked(H5Acreate2(object, name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
              "creating attribute " + name),
      H5Aclose);
  // H5Awrite rejects a null buffer, which an empty std::vector may hand over.
  if (!dims.empty() && dims[0] == 0) return;
  checked(H5Awrite(attribute.get(), memory_type, data), "writing attribute " + name);
}

void set_string(hid_t object, const std::string& name, const std::string& value) {
  const std::string text = valid_utf8(value);
  const char* pointer = text.c_str();
  const H5Handle type = string_type();
  set_attribute(object, name, type.get(), type.get(), {}, &pointer);
}

void set_strings(hid_t object, const std::string& name, const std::vector<std::string>& values) {
  std::vector<std::string> texts;
  for (const auto& value : values) texts.push_back(valid_utf8(value));
  std::vector<const char*> pointers;
  for (const auto& text : texts) pointers.push_back(text.c_str());
  const H5Handle type = string_type();
  set_attribute(object, name, type.get(), type.get(), {pointers.size()}, pointers.data());
}

void set_double(hid_t object, const std::string& name, double value) {
  set_attribute(object, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {}, &value);
}

void set_int(hid_t object, const std::string& name, std::int64_t value) {
  set_attribute(object, name, H5T_STD_I64LE, H5T_NATIVE_INT64, {}, &value);
}

void set_ints(hid_t object, const std::string& name, const std::vector<std::int64_t>& values) {
  set_attribute(object, name, H5T_STD_I64LE, H5T_NATIVE_INT64, {values.size()}, values.data());
}

H5Handle create_group(hid_t parent, const std::string& name) {
  // Tracking creation order keeps model parts in interface order for readers that honour it.
  const H5Handle properties(checked(H5Pcreate(H5P_GROUP_CREATE), "H5Pcreate"), H5Pclose);
  checked(
      H5Pset_link_creation_order(properties.get(), H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED),
      "H5Pset_link_creation_order");
  return {checked(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, properties.get(), H5P_DEFAULT),
                  "creating group " + name),
          H5Gclose};
}

/// A dataset of fixed shape, written once (model part ids and coordinates).
void write_fixed(hid_t parent, const std::string& name, hid_t file_type, hid_t memory_type,
                 const std::vector<hsize_t>& dims, const void* data, const char* unit) {
  const H5Handle space = dataspace(dims);
  const H5Handle dataset(checked(H5Dcreate2(parent, name.c_str(), file_type, space.get(),
                                            H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                                 "creating dataset " + name),
                         H5Dclose);
  if (unit) set_string(dataset.get(), "unit", unit);
  if (std::find(dims.begin(), dims.end(), hsize_t{0}) != dims.end()) return;
  checked(H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
          "writing dataset " + name);
}

std::string object_name(hid_t object) {
  char name[256] = "?";
  H5Iget_name(object, name, sizeof name);
  return name;
}

std::vector<std::string> member_names(hid_t group) {
  H5G_info_t info;
  checked(H5Gget_info(group, &info), "H5Gget_info");
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t length = checked(
        H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT),
        "H5Lget_name_by_idx");
    std::string name(std::size_t(length), '\0');
    checked(H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(),
                               name.size() + 1, H5P_DEFAULT),
            "H5Lget_name_by_idx");
    names.push_back(std::move(name));
  }
  return names;
}

std::vector<hsize_t> dataset_shape(hid_t dataset) {
  const H5Handle space(checked(H5Dget_space(dataset), "H5Dget_space"), H5Sclose);
  const int rank = checked(H5Sget_simple_extent_ndims(space.get()), "H5Sget_simple_extent_ndims");
  std::vector<hsize_t> dims(std::size_t(rank), 0);
  if (rank > 0)
    checked(H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr),
            "H5Sget_simple_extent_dims");
  return dims;
}

std::size_t element_count(hid_t dataset) {
  const H5Handle space(checked(H5Dget_space(dataset), "H5Dget_space"), H5Sclose);
  return std::size_t(
      checked(H5Sget_simple_extent_npoints(space.get()), "H5Sget_simple_extent_npoints"));
}

std::vector<double> read_doubles(hid_t dataset) {
  std::vector<double> values(element_count(dataset));
  if (!values.empty())
    checked(H5Dread(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
            "reading " + object_name(dataset));
  return values;
}

namespace {

H5Handle open_attribute(hid_t location, const std::string& object, const std::string& name) {
  return {checked(H5Aopen_by_name(location, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
                  "opening attribute " + object + "@" + name),
          H5Aclose};
}

std::size_t attribute_count(hid_t attribute) {
  const H5Handle space(checked(H5Aget_space(attribute), "H5Aget_space"), H5Sclose);
  return std::size_t(
      checked(H5Sget_simple_extent_npoints(space.get()), "H5Sget_simple_extent_npoints"));
}

}  // namespace

std::vector<double> read_doubles_attribute(hid_t location, const std::string& object,
                                           const std::string& name) {
  const H5Handle attribute = open_attribute(location, object, name);
  std::vector<double> values(attribute_count(attribute.get()));
  if (!values.empty())
    checked(H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, values.data()),
            "reading attribute " + object + "@" + name);
  return values;
}

std::vector<std::string> read_strings_attribute(hid_t location, const std::string& object,
                                                const std::string& name) {
  const H5Handle attribute = open_attribute(location, object, name);
  const H5Handle type = string_type();
  std::vector<char*> pointers(attribute_count(attribute.get()), nullptr);
  if (!pointers.empty())
    checked(H5Aread(attribute.get(), type.get(), pointers.data()),
            "reading attribute " + object + "@" + name);
  std::vector<std::string> values;
  for (char* text : pointers) {
    values.emplace_back(text ? text : "");
    H5free_memory(text);
  }
  return values;
}

}  // namespace cocopp::hdf5
