// nearest: each target point takes the value of its nearest source point.
#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "mappers/interpolators/interpolator.hpp"
#include "mappers/interpolators/sparse_rows.hpp"

namespace cocopp {
namespace {

class Nearest : public Interpolator {
 public:
  using Interpolator::Interpolator;

 protected:
  void build(const Eigen::MatrixXd& source, const Eigen::MatrixXd& target) override {
    std::vector<Eigen::Index> nearest_source(static_cast<std::size_t>(target.rows()));
    Eigen::VectorXd distances(target.rows());
    PointSearch::Neighbours nearest;
    Eigen::RowVectorXd query(target.cols());
    for (const Eigen::Index t : target_order()) {
      query = target.row(t);
      source_search().nearest(query.data(), 1, nearest);
      nearest_source[static_cast<std::size_t>(t)] = nearest.indices[0];
      distances(t) = std::sqrt(nearest.squared_distances[0]);
    }
    SparseRows rows(target.rows(), source.rows(), 1);
    for (const Eigen::Index s : nearest_source) {
      rows.add(s, 1.0);
      rows.end_row();
    }
    matrix_ = rows.finish();
    record_distances(distances);
  }
};

}  // namespace

COCOPP_REGISTER(InterpolatorRegistry, "nearest", Nearest)

}  // namespace cocopp
