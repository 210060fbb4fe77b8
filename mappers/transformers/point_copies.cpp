#include "mappers/transformers/point_copies.hpp"

#include <stdexcept>

namespace cocopp {

void PointCopies::reset(Eigen::Index points) {
  points_ = points;
  copies_.clear();
  copies_per_point_.assign(static_cast<std::size_t>(points), 0);
}

void PointCopies::add_copy(Eigen::Index origin, const Eigen::Matrix3d& to_copy) {
  copies_.push_back({origin, to_copy});
  ++copies_per_point_[static_cast<std::size_t>(origin)];
}

void PointCopies::check(const RowMatrix& values, Eigen::Index rows, const char* what) const {
  if (values.rows() != rows)
    throw std::invalid_argument("transformer: expected values at " + std::to_string(rows) + " " +
                                what + ", got " + std::to_string(values.rows()) + " rows");
  if (values.cols() != 1 && values.cols() != 3)
    throw std::invalid_argument(
        "transformer: values must have 1 (scalar) or 3 (vector) components, got " +
        std::to_string(values.cols()));
}

RowMatrix PointCopies::forward(const RowMatrix& values) const {
  check(values, points_, "points");
  RowMatrix out(copies(), values.cols());
  for (Eigen::Index j = 0; j < copies(); ++j) {
    const Copy& copy = copies_[static_cast<std::size_t>(j)];
    if (values.cols() == 1)
      out(j, 0) = values(copy.origin, 0);
    else
      out.row(j) = values.row(copy.origin) * copy.to_copy.transpose();
  }
  return out;
}

RowMatrix PointCopies::backward(const RowMatrix& values) const {
  check(values, copies(), "transformed points");
  RowMatrix out = RowMatrix::Zero(points_, values.cols());
  for (Eigen::Index j = 0; j < copies(); ++j) {
    const Copy& copy = copies_[static_cast<std::size_t>(j)];
    if (values.cols() == 1)
      out(copy.origin, 0) += values(j, 0);
    else
      out.row(copy.origin) += values.row(j) * copy.to_copy;  // (to_copy^T v)^T
  }
  for (Eigen::Index i = 0; i < points_; ++i)
    out.row(i) /= copies_per_point_[static_cast<std::size_t>(i)];
  return out;
}

int required_direction(const Settings& settings, const std::string& key) {
  const std::string name = settings.required_choice(key, {"x", "y", "z"});
  return name[0] - 'x';
}

const char* direction_name(int index) {
  static const char* const names[] = {"x", "y", "z"};
  return names[index];
}

}  // namespace cocopp
