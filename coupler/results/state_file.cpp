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
  const std::vector<hsize_t> dims = dataset_shape(dataset);
  if (dims.size() > 2) throw H5Error(object_name(dataset) + " has more than 2 dimensions");
  const std::vector<double> values = read_doubles(dataset);
  const Eigen::Index rows = dims.empty() ? 1 : Eigen::Index(dims[0]);
  const Eigen::Index cols = dims.size() == 2 ? Eigen::Index(dims[1]) : 1;
  return {Eigen::MatrixXd(Eigen::Map<const RowMajor>(values.data(), rows, cols)), int(dims.size())};
}

void read_node(hid_t group, State& node) {
  for (const std::string& name : member_names(group)) {
    const H5Handle object(checked(H5Oopen(group, name.c_str(), H5P_DEFAULT), "opening " + name),
                          H5Oclose);
    if (H5Iget_type(object.get()) == H5I_GROUP)
      read_node(object.get(), node.group(name));
    else
      node.set_array(name, read_array(object.get()));
  }
}

}  // namespace

void write_state_file(const std::filesystem::path& file, const SavedState& saved) {
  const QuietErrors quiet;
  std::filesystem::path temporary = file;
  temporary += ".writing";
  try {
    if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
    // H5Fcreate would follow a link planted at the temporary name and overwrite its target.
    std::filesystem::remove(temporary);
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
    saved.step = int(read_doubles_attribute(h5.get(), "/", "step").at(0));
    saved.time = read_doubles_attribute(h5.get(), "/", "time").at(0);
    saved.coupled_solver = read_strings_attribute(h5.get(), "/", "coupled_solver").at(0);
    read_node(h5.get(), saved.state);
    return saved;
  } catch (const std::exception& error) {
    throw std::runtime_error("cannot read the coupled-solver state " + file.string() + ": " +
                             error.what());
  }
}

}  // namespace cocopp
