#include "solver_wrappers/tube/tube_input.hpp"

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

}  // namespace cocopp::tube
