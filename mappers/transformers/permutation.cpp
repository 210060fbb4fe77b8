// permutation: swap the coordinate axes of one side, e.g. [2, 0, 1] when the other solver's
// x is this solver's z. Points and vectors are permuted, scalars copied; backward permutes back.
#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "mappers/transformers/point_copies.hpp"

namespace cocopp {
namespace {

/// The `permutation` key: three distinct integers 0..2; new coordinate i = old coordinate p[i].
std::vector<int> read_permutation(const Settings& settings) {
  const auto values = settings.required<std::vector<double>>("permutation");
  if (values.size() != 3)
    settings.fail("permutation", "expected a list of 3 axis indices (0 = x, 1 = y, 2 = z), got " +
                                     std::to_string(values.size()) + " entries");
  std::vector<int> permutation;
  for (double value : values) {
    if (value != std::floor(value) || value < 0 || value > 2)
      settings.fail("permutation", "entries must be the axis indices 0, 1 or 2, got " +
                                       (std::ostringstream() << value).str());
    permutation.push_back(static_cast<int>(value));
  }
  if (std::set<int>(permutation.begin(), permutation.end()).size() != 3)
    settings.fail("permutation",
                  "must hold each of 0, 1, 2 once, got [" + std::to_string(permutation[0]) + ", " +
                      std::to_string(permutation[1]) + ", " + std::to_string(permutation[2]) + "]");
  return permutation;
}

class Permutation : public PointCopies {
 public:
  explicit Permutation(const Settings& settings) : PointCopies(Side::kSource) {
    const std::vector<int> p = read_permutation(settings);
    matrix_.setZero();
    for (int i = 0; i < 3; ++i) matrix_(i, p[static_cast<std::size_t>(i)]) = 1.0;
  }

  Coordinates transform_points(const Coordinates& points) override {
    reset(points.rows());
    for (Eigen::Index i = 0; i < points.rows(); ++i) add_copy(i, matrix_);
    return points * matrix_.transpose();  // rows: (P x)^T
  }
  bool keeps_totals() const override { return true; }

 private:
  Eigen::Matrix3d matrix_;  ///< new = matrix_ * old
};

}  // namespace

COCOPP_REGISTER(TransformerRegistry, "permutation", Permutation)

}  // namespace cocopp
