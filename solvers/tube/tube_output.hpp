#pragma once
// Legacy VTK output of the tube solvers, one polydata file per written time step: the cell
// centres at (0, r0 + dr_i, z_i), joined by one polyline, with point data. ParaView opens
// the numbered series <directory>/<solver>_000010.vtk, ... as one time-dependent data set.
#include <Eigen/Dense>
#include <string>
#include <vector>

#include "solvers/tube/tube_input.hpp"

namespace cocopp::tube {

/// Point data: a scalar (one value per point) or a vector (3 values per point, x y z).
struct PointField {
  std::string name;
  Eigen::VectorXd values;
  bool is_vector = false;
};

/// "<directory>/<solver>_<step padded to 6 digits>.vtk"
std::string output_file_name(const OutputSettings& output, const std::string& solver, int step);

/// Write the file for `step` if the output interval says so (creates the directory), with its
/// `time` as field data TIME, which ParaView takes as the time of a file series.
void write_output(const OutputSettings& output, const std::string& solver, int step, double time,
                  const TubeGeometry& geometry, const Eigen::VectorXd& displacement,
                  const std::vector<PointField>& fields);

/// The radial displacement as interface vectors (0, dr_i, 0).
Eigen::VectorXd radial_vectors(const Eigen::VectorXd& displacement);

}  // namespace cocopp::tube
