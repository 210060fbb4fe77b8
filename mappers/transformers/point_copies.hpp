#pragma once
// The common machinery of the transformers: every point of this side stands for one or more
// transformed points (its copies), and a vector value goes to a copy through a 3 x 3 matrix
// (a permutation, a rotation about the axis, a projection out of the depth direction).
// `forward` copies values to the copies; `backward` brings each copy back through the
// transposed matrix and averages the copies of a point. Scalars are copied and averaged.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "mappers/transformers/transformer.hpp"

namespace cocopp {

class PointCopies : public Transformer {
 public:
  explicit PointCopies(Side side) : side_(side) {}

  Side side() const override { return side_; }
  /// Throws std::invalid_argument unless `values` has one row per point given to the last
  /// transform_points and 1 (scalar) or 3 (vector) columns.
  RowMatrix forward(const RowMatrix& values) const override;
  /// Throws std::invalid_argument unless `values` has one row per transformed point and 1 or
  /// 3 columns.
  RowMatrix backward(const RowMatrix& values) const override;

  /// Transformed points so far (for tests and messages).
  Eigen::Index copies() const { return static_cast<Eigen::Index>(copies_.size()); }

 protected:
  /// Forget earlier copies; `points` points of this side follow.
  void reset(Eigen::Index points);
  /// The next transformed point is a copy of point `origin`; a vector at `origin` becomes
  /// `to_copy * vector` there. Every point needs at least one copy before values are mapped.
  void add_copy(Eigen::Index origin, const Eigen::Matrix3d& to_copy);

 private:
  struct Copy {
    Eigen::Index origin;
    Eigen::Matrix3d to_copy;
  };
  void check(const RowMatrix& values, Eigen::Index rows, const char* what) const;

  Side side_;
  Eigen::Index points_ = 0;
  std::vector<Copy> copies_;
  std::vector<int> copies_per_point_;
};

/// Index (0, 1, 2) of a required direction key with value x, y or z.
int required_direction(const Settings& settings, const std::string& key);
/// "x", "y" or "z".
const char* direction_name(int index);

}  // namespace cocopp
