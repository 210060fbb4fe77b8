#include "coupler/results/hdf5_copy.hpp"

#include <algorithm>

#include "coupler/results/hdf5_support.hpp"

namespace cocopp::hdf5 {
namespace {

/// A group's link names in creation order where the group tracks it (the writer's groups do),
/// else in name order.
std::vector<std::string> links_in_order(hid_t group) {
  const H5Handle properties(checked(H5Gget_create_plist(group), "H5Gget_create_plist"), H5Pclose);
  unsigned flags = 0;
  checked(H5Pget_link_creation_order(properties.get(), &flags), "H5Pget_link_creation_order");
  const H5_index_t index = (flags & H5P_CRT_ORDER_INDEXED) ? H5_INDEX_CRT_ORDER : H5_INDEX_NAME;
  H5G_info_t info;
  checked(H5Gget_info(group, &info), "H5Gget_info");
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t length =
        checked(H5Lget_name_by_idx(group, ".", index, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT),
                "H5Lget_name_by_idx");
    std::string name(std::size_t(length), '\0');
    checked(H5Lget_name_by_idx(group, ".", index, H5_ITER_INC, i, name.data(), name.size() + 1,
                               H5P_DEFAULT),
            "H5Lget_name_by_idx");
    names.push_back(std::move(name));
  }
  return names;
}

/// A fresh group (or file) creation list with the link creation order `source`'s has. (The
/// source's own list carries the addresses of its link storage: a group created with it points
/// into the other file.)
H5Handle creation_order_like(hid_t source, hid_t fresh_class) {
  unsigned flags = 0;
  checked(H5Pget_link_creation_order(source, &flags), "H5Pget_link_creation_order");
  H5Handle properties(checked(H5Pcreate(fresh_class), "H5Pcreate"), H5Pclose);
  checked(H5Pset_link_creation_order(properties.get(), flags), "H5Pset_link_creation_order");
  return properties;
}

/// A fresh dataset creation list with `source`'s chunks (none: contiguous).
H5Handle chunks_like(hid_t source) {
  H5Handle properties(checked(H5Pcreate(H5P_DATASET_CREATE), "H5Pcreate"), H5Pclose);
  if (checked(H5Pget_layout(source), "H5Pget_layout") != H5D_CHUNKED) return properties;
  const int rank = checked(H5Pget_chunk(source, 0, nullptr), "H5Pget_chunk");
  std::vector<hsize_t> chunk(static_cast<std::size_t>(rank));
  checked(H5Pget_chunk(source, rank, chunk.data()), "H5Pget_chunk");
  checked(H5Pset_chunk(properties.get(), rank, chunk.data()), "H5Pset_chunk");
  return properties;
}

H5Handle memory_type_of(hid_t file_type) {
  return {checked(H5Tget_native_type(file_type, H5T_DIR_DEFAULT), "H5Tget_native_type"), H5Tclose};
}

/// Values read with `memory_type` into `space`'s selection; variable-length strings are
/// returned to HDF5 when it goes.
class ReadBuffer {
 public:
  ReadBuffer(hid_t memory_type, hid_t space)
      : memory_type_(memory_type),
        space_(space),
        bytes_(std::size_t(checked(H5Sget_select_npoints(space), "H5Sget_select_npoints")) *
               H5Tget_size(memory_type)) {}
  ~ReadBuffer() {
    if (filled_ &&
        (H5Tdetect_class(memory_type_, H5T_VLEN) > 0 || H5Tis_variable_str(memory_type_) > 0))
      H5Dvlen_reclaim(memory_type_, space_, H5P_DEFAULT, bytes_.data());
  }
  ReadBuffer(const ReadBuffer&) = delete;
  ReadBuffer& operator=(const ReadBuffer&) = delete;

  bool empty() const { return bytes_.empty(); }
  void* fill() {
    filled_ = true;
    return bytes_.data();
  }
  const void* data() const { return bytes_.data(); }

 private:
  hid_t memory_type_;
  hid_t space_;
  std::vector<unsigned char> bytes_;
  bool filled_ = false;
};

herr_t copy_one_attribute(hid_t from, const char* name, const H5A_info_t*, void* to) {
  const H5Handle attribute(H5Aopen(from, name, H5P_DEFAULT), H5Aclose);
  if (!attribute.valid()) return -1;
  const H5Handle file_type(H5Aget_type(attribute.get()), H5Tclose);
  const H5Handle space(H5Aget_space(attribute.get()), H5Sclose);
  const H5Handle memory_type(H5Tget_native_type(file_type.get(), H5T_DIR_DEFAULT), H5Tclose);
  if (!file_type.valid() || !space.valid() || !memory_type.valid()) return -1;
  const H5Handle copy(H5Acreate2(*static_cast<hid_t*>(to), name, file_type.get(), space.get(),
                                 H5P_DEFAULT, H5P_DEFAULT),
                      H5Aclose);
  if (!copy.valid()) return -1;
  ReadBuffer values(memory_type.get(), space.get());
  if (values.empty()) return 0;
  if (H5Aread(attribute.get(), memory_type.get(), values.fill()) < 0) return -1;
  return H5Awrite(copy.get(), memory_type.get(), values.data()) < 0 ? -1 : 0;
}

void copy_attributes(hid_t from, hid_t to, const std::string& what) {
  hsize_t position = 0;
  checked(H5Aiterate2(from, H5_INDEX_NAME, H5_ITER_INC, &position, copy_one_attribute, &to),
          "copying the attributes of " + what);
}

void copy_dataset(hid_t from, hid_t parent, const std::string& name, const std::string& path,
                  const RowsToKeep& keep) {
  const std::string what = "copying " + path;
  const H5Handle source(checked(H5Dopen2(from, name.c_str(), H5P_DEFAULT), what), H5Dclose);
  const H5Handle file_type(checked(H5Dget_type(source.get()), what), H5Tclose);
  const H5Handle source_properties(checked(H5Dget_create_plist(source.get()), what), H5Pclose);
  const H5Handle properties = chunks_like(source_properties.get());
  const H5Handle source_space(checked(H5Dget_space(source.get()), what), H5Sclose);
  const int rank = checked(H5Sget_simple_extent_ndims(source_space.get()), what);
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank)), max_dims(dims.size());
  if (rank > 0)
    checked(H5Sget_simple_extent_dims(source_space.get(), dims.data(), max_dims.data()), what);
  if (rank > 0 && max_dims[0] == H5S_UNLIMITED) {
    dims[0] = std::min(dims[0], keep(path, dims[0]));
    std::vector<hsize_t> start(dims.size(), 0);
    checked(H5Sselect_hyperslab(source_space.get(), H5S_SELECT_SET, start.data(), nullptr,
                                dims.data(), nullptr),
            what);
  }
  const H5Handle space = dataspace(dims, rank > 0 ? max_dims.data() : nullptr);
  const H5Handle copy(checked(H5Dcreate2(parent, name.c_str(), file_type.get(), space.get(),
                                         H5P_DEFAULT, properties.get(), H5P_DEFAULT),
                              what),
                      H5Dclose);
  copy_attributes(source.get(), copy.get(), path);
  const H5Handle memory_type = memory_type_of(file_type.get());
  const H5Handle memory_space = dataspace(dims);
  ReadBuffer values(memory_type.get(), memory_space.get());
  if (values.empty()) return;
  checked(H5Dread(source.get(), memory_type.get(), memory_space.get(), source_space.get(),
                  H5P_DEFAULT, values.fill()),
          "reading " + path);
  checked(H5Dwrite(copy.get(), memory_type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
          what);
}

void copy_members(hid_t from, hid_t to, const std::string& prefix, const RowsToKeep& keep,
                  const std::vector<std::string>& skip) {
  for (const std::string& name : links_in_order(from)) {
    const std::string path = prefix + name;
    if (std::find(skip.begin(), skip.end(), path) != skip.end()) continue;
    const H5Handle object(checked(H5Oopen(from, name.c_str(), H5P_DEFAULT), "opening " + path),
                          H5Oclose);
    switch (H5Iget_type(object.get())) {
      case H5I_GROUP: {
        const H5Handle source_properties(checked(H5Gget_create_plist(object.get()), path),
                                         H5Pclose);
        const H5Handle properties = creation_order_like(source_properties.get(), H5P_GROUP_CREATE);
        const H5Handle group(
            checked(H5Gcreate2(to, name.c_str(), H5P_DEFAULT, properties.get(), H5P_DEFAULT),
                    "creating group " + path),
            H5Gclose);
        copy_attributes(object.get(), group.get(), path);
        copy_members(object.get(), group.get(), path + "/", keep, skip);
        break;
      }
      case H5I_DATASET:
        copy_dataset(from, to, name, path, keep);
        break;
      default:
        throw H5Error("copying " + path + " failed: it is neither a group nor a dataset");
    }
  }
}

}  // namespace

void copy_file(const std::filesystem::path& from, const std::filesystem::path& to,
               const RowsToKeep& keep, const std::vector<std::string>& skip) {
  const H5Handle source(checked(H5Fopen(from.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "opening"),
                        H5Fclose);
  const H5Handle source_properties(
      checked(H5Fget_create_plist(source.get()), "H5Fget_create_plist"), H5Pclose);
  const H5Handle properties = creation_order_like(source_properties.get(), H5P_FILE_CREATE);
  const H5Handle copy(
      checked(H5Fcreate(to.c_str(), H5F_ACC_TRUNC, properties.get(), H5P_DEFAULT), "creating"),
      H5Fclose);
  const H5Handle source_root(checked(H5Gopen2(source.get(), "/", H5P_DEFAULT), "opening /"),
                             H5Gclose);
  const H5Handle copy_root(checked(H5Gopen2(copy.get(), "/", H5P_DEFAULT), "opening /"), H5Gclose);
  copy_attributes(source_root.get(), copy_root.get(), "the root group");
  copy_members(source_root.get(), copy_root.get(), "", keep, skip);
  checked(H5Fflush(copy.get(), H5F_SCOPE_GLOBAL), "flushing the copy");
}

}  // namespace cocopp::hdf5
