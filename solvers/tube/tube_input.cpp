#include "solvers/tube/tube_input.hpp"

#include <stdexcept>

namespace cocopp::tube {

double TubeGeometry::area() const {
  return kPi * diameter * diameter / 4.0;
}

Eigen::VectorXd TubeGeometry::cell_centres() const {
  const double dz = cell_size();
  Eigen::VectorXd z(cells);
  for (int i = 0; i < cells; ++i) z[i] = -length / 2.0 + dz / 2.0 + i * dz;
  return z;
}

TubeGeometry TubeGeometry::read(const Settings& input) {
  TubeGeometry geometry;
  geometry.length = input.required_in_range("length", Range::positive());
  geometry.diameter = input.required_in_range("diameter", Range::positive());
  // Two cells at least: the boundary rows extrapolate from the two cells next to each end.
  geometry.cells = input.required_int_in_range("cells", 2);
  return geometry;
}

OutputSettings OutputSettings::read(const Settings& input) {
  const Settings output = input.child_or_empty("output");
  OutputSettings settings;
  settings.interval = output.get_int_in_range("interval", settings.interval, 0);
  settings.directory = output.get<std::string>("directory", settings.directory);
  if (settings.directory.empty()) output.fail("directory", "must not be empty");
  return settings;
}

double read_residual_atol(const Settings& input) {
  return input.has("residual_atol") ? input.required_in_range("residual_atol", Range::positive())
                                    : 0.0;
}

void require_residual_atol(double residual_atol, const std::string& model,
                           const std::string& measure) {
  if (residual_atol <= 0.0)
    throw std::runtime_error("solver-coupling convergence needs residual_atol in the " + model +
                             "'s input file: the " + measure +
                             " (m) below which a solve counts as converged at its first "
                             "iteration, e.g. residual_atol: 1.0e-12");
}

}  // namespace cocopp::tube
