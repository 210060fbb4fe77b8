#pragma once
// A model part: a named set of interface points with ids and initial coordinates.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace cocopp {

using Coordinates = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

struct ModelPart {
  std::string name;
  std::vector<std::int64_t> ids;
  Coordinates coordinates;  ///< initial coordinates, one row (x, y, z) per point

  std::size_t size() const { return ids.size(); }
};

}  // namespace cocopp
