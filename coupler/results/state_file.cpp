#include "coupler/results/state_file.hpp"

#include <stdexcept>
#include <vector>

#include "coupler/results/hdf5_support.hpp"

#ifndef COCOPP_VERSION
#define COCOPP_VERSION "unknown"
#endif

namespace cocopp {
namespace {

using namespace hdf5;
using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

void write_node(hid_t group, const State& node) {
  for (const auto& [name, array] : node.arrays()) {
    std::vector<hsize_t> dims;
    if (array.rank >= 1) dims.push_back(hsize_t(array.values.rows()));
    if (array.rank == 2) dims.push_back(hsize_t(array.values.cols()));
    const RowMajor values = array.values;  // h5py reads C order
    write_fixed(group, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, dims, values.data(), nullptr);
  }
  for (const auto& [name, child] : node.groups()) {
    const H5Handle child_group = create_group(group, name);
    write_node(child_group.get(), child);
  }
}

State::Array read_array(hid_t dataset) {
  const H5Handle space(checked(H5Dget_space(dataset), "H5Dget_space"), H5Sclose);
  const int rank = checked(H5Sget_simple_extent_ndims(space.get()), "H5Sget_simple_extent_ndims");
  if (rank > 2) throw H5Error(object_name(dataset) + " has more than 2 dimensions");
  hsize_t dims[2] = {1, 1};
  if (rank > 0) H5Sget_simple_extent_dims(space.get(), dims, nullptr);
  RowMajor values(Eigen::Index(dims[0]), Eigen::Index(rank == 2 ? dims[1] : 1));
  if (values.size() > 0)
    checked(H5Dread(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
            "reading " + object_name(dataset));
  return {Eigen::MatrixXd(values), rank};
}

void read_node(hid_t group, State& node) {
  H5G_info_t info;
  checked(H5Gget_info(group, &info), "H5Gget_info");
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t length = checked(
        H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT),
        "H5Lget_name_by_idx");
    std::string name(std::size_t(length), '\0');
    H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size() + 1,
                       H5P_DEFAULT);
    const H5Handle object(checked(H5Oopen(group, name.c_str(), H5P_DEFAULT), "opening " + name),
                          H5Oclose);
    if (H5Iget_type(object.get()) == H5I_GROUP)
      read_node(object.get(), node.group(name));
    else
      node.set_array(name, read_array(object.get()));
  }
}

template <class T>
T read_attribute(hid_t object, const char* name, hid_t memory_type) {
  const H5Handle attribute(
      checked(H5Aopen(object, name, H5P_DEFAULT), "opening attribute " + std::string(name)),
      H5Aclose);
  T value{};
  checked(H5Aread(attribute.get(), memory_type, &value), "reading attribute " + std::string(name));
  return value;
}

std::string read_string_attribute(hid_t object, const char* name) {
  const H5Handle attribute(
      checked(H5Aopen(object, name, H5P_DEFAULT), "opening attribute " + std::string(name)),
      H5Aclose);
  const H5Handle type = string_type();
  char* text = nullptr;
  checked(H5Aread(attribute.get(), type.get(), &text), "reading attribute " + std::string(name));
  std::string value = text ? text : "";
  H5free_memory(text);
  return value;
}

}  // namespace

void write_state_file(const std::filesystem::path& file, const SavedState& saved) {
  const QuietErrors quiet;
  std::filesystem::path temporary = file;
  temporary += ".writing";
  try {
    if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
    {
      const H5Handle h5(
          checked(H5Fcreate(temporary.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT),
                  "creating the file"),
          H5Fclose);
      set_int(h5.get(), "step", saved.step);
      set_double(h5.get(), "time", saved.time);
      set_string(h5.get(), "coupled_solver", saved.coupled_solver);
      set_string(h5.get(), "cocopp_version", COCOPP_VERSION);
      write_node(h5.get(), saved.state);
    }
    std::filesystem::rename(temporary, file);
  } catch (const std::exception& error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error("cannot write the coupled-solver state " + file.string() + ": " +
                             error.what());
  }
}

SavedState read_state_file(const std::filesystem::path& file) {
  const QuietErrors quiet;
  try {
    if (!std::filesystem::exists(file)) throw std::runtime_error("no such file");
    const H5Handle h5(checked(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "opening"),
                      H5Fclose);
    SavedState saved;
    saved.step = int(read_attribute<std::int64_t>(h5.get(), "step", H5T_NATIVE_INT64));
    saved.time = read_attribute<double>(h5.get(), "time", H5T_NATIVE_DOUBLE);
    saved.coupled_solver = read_string_attribute(h5.get(), "coupled_solver");
    read_node(h5.get(), saved.state);
    return saved;
  } catch (const std::exception& error) {
    throw std::runtime_error("cannot read the coupled-solver state " + file.string() + ": " +
                             error.what());
  }
}

}  // namespace cocopp
