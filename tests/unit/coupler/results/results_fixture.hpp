#pragma once
// A small run shared by the results tests: interfaces of two model parts, step records with
// ragged residual histories, and data that differs per step, point and component. Also the
// HDF5 C API readers the tests check the file with.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/data/interface.hpp"
#include "coupler/results/results_writer.hpp"
#include "coupler/results/step_record.hpp"

namespace cocopp::test {

inline std::shared_ptr<ModelPart> model_part(const std::string& name, int points, double z0) {
  auto part = std::make_shared<ModelPart>();
  part->name = name;
  part->coordinates.resize(points, 3);
  for (int i = 0; i < points; ++i) {
    part->ids.push_back(100 * (name.size()) + i);
    part->coordinates.row(i) << 0.005, 0.0, z0 + 0.01 * i;
  }
  return part;
}

struct Interfaces {
  Interface x, y;
};

/// x: displacement on "wall" (4 points) and "inlet" (2); y: pressure and traction on "wall",
/// pressure on "inlet".
inline Interfaces make_interfaces() {
  const auto wall = model_part("wall", 4, 0.0);
  const auto inlet = model_part("inlet", 2, -0.01);
  return {Interface({{wall, {"displacement"}}, {inlet, {"displacement"}}}),
          Interface({{wall, {"pressure", "traction"}}, {inlet, {"pressure"}}})};
}

/// Distinct values for every step and index, so a value in the wrong row or place shows.
inline void fill(Interfaces& interfaces, int step) {
  Eigen::VectorXd x(interfaces.x.size()), y(interfaces.y.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = 1e-3 * step + 1e-6 * i;
  for (Eigen::Index i = 0; i < y.size(); ++i) y[i] = 1000.0 * step - i;
  interfaces.x.set_data(x);
  interfaces.y.set_data(y);
}

inline RunDescription make_run(int steps) {
  RunDescription run;
  run.case_file = "examples/tube/case.yaml";
  run.coupled_solver = "iqni";
  run.solver_names = {"tube_flow", "tube_structure"};
  run.delta_t = 0.01;
  run.timestep_start = 0;
  run.number_of_timesteps = steps;
  return run;
}

/// Step 2 is accepted unconverged; iterations cycle 2, 3, 1, ...
inline StepRecord make_record(int step) {
  StepRecord r;
  r.step = step;
  r.time = 0.01 * step;
  r.iterations = 1 + (step + 1) % 3;
  for (int i = 0; i < r.iterations; ++i) r.residual_norms.push_back(std::pow(10.0, -i) / step);
  r.wall_time = 0.1 * step;
  r.solver_times = {0.03 * step, 0.05 * step};
  r.coupler_time = r.wall_time - r.solver_times[0] - r.solver_times[1];
  r.converged = step != 2;
  return r;
}

/// Writes steps 1..steps; closes with `status` unless it is empty (then the file stays open
/// and the writer is returned).
inline std::unique_ptr<ResultsWriter> write_run(const std::filesystem::path& file, int steps,
                                                const std::string& status = "completed") {
  Interfaces interfaces = make_interfaces();
  auto writer = std::make_unique<ResultsWriter>(file, make_run(steps), interfaces.x, interfaces.y);
  for (int step = 1; step <= steps; ++step) {
    fill(interfaces, step);
    writer->write_step(make_record(step), interfaces.x, interfaces.y);
  }
  if (!status.empty()) writer->close(status, "all " + std::to_string(steps) + " steps done");
  return writer;
}

/// A fresh directory for one test, under the test's working directory (kept for inspection).
inline std::filesystem::path test_directory() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const auto dir = std::filesystem::current_path() / "results_test_output" /
                   (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// ---- reading back with the HDF5 C API ----

inline H5Handle open_file(const std::filesystem::path& file) {
  return {H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
}

struct Array {
  std::vector<hsize_t> shape;
  std::vector<double> values;
};

inline std::vector<hsize_t> shape_of(hid_t space) {
  std::vector<hsize_t> dims(H5Sget_simple_extent_ndims(space));
  H5Sget_simple_extent_dims(space, dims.data(), nullptr);
  return dims;
}

/// Any numeric dataset, converted to double.
inline Array read_dataset(hid_t file, const std::string& path) {
  const H5Handle dataset(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose);
  if (!dataset.valid()) throw std::runtime_error("no dataset " + path);
  const H5Handle space(H5Dget_space(dataset.get()), H5Sclose);
  Array out{shape_of(space.get()), {}};
  out.values.resize(H5Sget_simple_extent_npoints(space.get()));
  if (!out.values.empty())
    H5Dread(dataset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, out.values.data());
  return out;
}

/// The 0/1 values of a dataset of the h5py bool enum, read in its own type.
inline std::vector<int> read_bools(hid_t file, const std::string& path) {
  const H5Handle dataset(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose);
  const H5Handle type(H5Dget_type(dataset.get()), H5Tclose);
  const H5Handle space(H5Dget_space(dataset.get()), H5Sclose);
  std::vector<std::int8_t> raw(H5Sget_simple_extent_npoints(space.get()));
  H5Dread(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, raw.data());
  return {raw.begin(), raw.end()};
}

inline H5Handle open_attribute(hid_t file, const std::string& object, const std::string& name) {
  return {H5Aopen_by_name(file, object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
}

inline std::vector<std::string> read_strings(hid_t file, const std::string& object,
                                             const std::string& name) {
  const H5Handle attribute = open_attribute(file, object, name);
  if (!attribute.valid()) throw std::runtime_error("no attribute " + object + "@" + name);
  const H5Handle space(H5Aget_space(attribute.get()), H5Sclose);
  const H5Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), H5T_VARIABLE);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  std::vector<char*> pointers(H5Sget_simple_extent_npoints(space.get()), nullptr);
  if (!pointers.empty()) H5Aread(attribute.get(), type.get(), pointers.data());
  std::vector<std::string> out;
  for (char* p : pointers) {
    out.emplace_back(p ? p : "");
    H5free_memory(p);
  }
  return out;
}

inline std::string read_string(hid_t file, const std::string& object, const std::string& name) {
  const auto strings = read_strings(file, object, name);
  return strings.empty() ? "" : strings.front();
}

/// Numeric attribute (scalar or array), converted to double.
inline std::vector<double> read_numbers(hid_t file, const std::string& object,
                                        const std::string& name) {
  const H5Handle attribute = open_attribute(file, object, name);
  if (!attribute.valid()) throw std::runtime_error("no attribute " + object + "@" + name);
  const H5Handle space(H5Aget_space(attribute.get()), H5Sclose);
  std::vector<double> out(H5Sget_simple_extent_npoints(space.get()));
  if (!out.empty()) H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, out.data());
  return out;
}

inline double read_number(hid_t file, const std::string& object, const std::string& name) {
  return read_numbers(file, object, name).at(0);
}

}  // namespace cocopp::test
