#pragma once
// What the three tube solver executables share: the `wall` model part they present to the
// coupler, the conversion between interface vectors and the models' per-cell values, and the
// command line (the input file argument).
#include <Eigen/Dense>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "solvers/sdk/solver_sdk.hpp"
#include "solvers/tube/tube_input.hpp"

namespace cocopp::tube {

/// One model part `wall`: m points with ids 0..m-1 at (0, r0, z_i).
inline sdk::ModelPart wall_model_part(const TubeGeometry& geometry,
                                      std::vector<std::string> input_variables,
                                      std::vector<std::string> output_variables) {
  sdk::ModelPart wall;
  wall.name = "wall";
  const Eigen::VectorXd z = geometry.cell_centres();
  for (int i = 0; i < geometry.cells; ++i) {
    wall.ids.push_back(i);
    wall.coordinates.insert(wall.coordinates.end(), {0.0, geometry.radius(), z[i]});
  }
  wall.input_variables = std::move(input_variables);
  wall.output_variables = std::move(output_variables);
  return wall;
}

inline std::vector<double> to_vector(const Eigen::VectorXd& values) {
  return std::vector<double>(values.data(), values.data() + values.size());
}

/// The y components of `cells` 3-component vectors starting at `offset` of `input`.
inline Eigen::VectorXd radial_component(const std::vector<double>& input, int cells,
                                        std::size_t offset = 0) {
  if (input.size() < offset + 3 * static_cast<std::size_t>(cells)) {
    throw std::runtime_error("tube solver: interface input has " + std::to_string(input.size()) +
                             " values, expected at least " +
                             std::to_string(offset + 3 * static_cast<std::size_t>(cells)));
  }
  Eigen::VectorXd radial(cells);
  for (int i = 0; i < cells; ++i) radial[i] = input[offset + 3 * i + 1];
  return radial;
}

/// argv[1] if given (and not an option), else the default file name in the working directory.
inline std::string input_file_argument(int argc, char** argv, const std::string& default_name) {
  if (argc > 1 && argv[1][0] != '-') return argv[1];
  return default_name;
}

}  // namespace cocopp::tube
