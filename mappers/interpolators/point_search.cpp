// PointSearch on nanoflann: one tree type per dimension (fixed-size distance loops are faster).
#include "mappers/interpolators/point_search.hpp"

#include <algorithm>
#include <limits>
#include <nanoflann.hpp>
#include <stdexcept>
#include <string>

namespace cocopp {

namespace {

/// nanoflann's view of the d x n coordinate matrix. It keeps the data pointer, not the matrix,
/// so that it stays valid when the owning PointSearch is moved.
struct CoordinatesAdaptor {
  const double* data;
  Eigen::Index dimension;
  Eigen::Index count;
  std::size_t kdtree_get_point_count() const { return static_cast<std::size_t>(count); }
  double kdtree_get_pt(Eigen::Index i, std::size_t dim) const {
    return data[i * dimension + static_cast<Eigen::Index>(dim)];
  }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;  // let nanoflann compute it
  }
};

/// Result set that stops at the first point, other than `self`, closer than the radius.
class FirstOtherPoint {
 public:
  FirstOtherPoint(double squared_radius, Eigen::Index self)
      : squared_radius_(squared_radius), self_(self) {}
  bool addPoint(double squared_distance, Eigen::Index index) {
    if (index == self_ || !(squared_distance < squared_radius_)) return true;
    found_ = index;
    return false;  // stop the search
  }
  double worstDist() const { return squared_radius_; }
  bool full() const { return true; }
  std::size_t size() const { return found_ < 0 ? 0 : 1; }
  Eigen::Index found() const { return found_; }

 private:
  double squared_radius_;
  Eigen::Index self_;
  Eigen::Index found_ = -1;
};

}  // namespace

class PointSearch::Tree {
 public:
  virtual ~Tree() = default;
  virtual std::size_t nearest(const double* query, std::size_t k, Eigen::Index* indices,
                              double* squared_distances) const = 0;
  virtual void within(const double* query, double squared_radius,
                      std::vector<std::pair<Eigen::Index, double>>& found) const = 0;
  virtual Eigen::Index other_within(const double* query, double squared_radius,
                                    Eigen::Index self) const = 0;
  virtual const std::vector<Eigen::Index>& order() const = 0;
};

template <int D>
class PointSearch::FixedTree : public PointSearch::Tree {
 public:
  explicit FixedTree(const Eigen::MatrixXd& coordinates)
      : adaptor_{coordinates.data(), coordinates.rows(), coordinates.cols()},
        index_(D, adaptor_, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {}

  std::size_t nearest(const double* query, std::size_t k, Eigen::Index* indices,
                      double* squared_distances) const override {
    nanoflann::KNNResultSet<double, Eigen::Index> result(k);
    result.init(indices, squared_distances);
    index_.findNeighbors(result, query, nanoflann::SearchParams());
    return result.size();
  }
  void within(const double* query, double squared_radius,
              std::vector<std::pair<Eigen::Index, double>>& found) const override {
    nanoflann::RadiusResultSet<double, Eigen::Index> result(squared_radius, found);
    index_.findNeighbors(result, query, nanoflann::SearchParams(32, 0.0f, false));
  }
  Eigen::Index other_within(const double* query, double squared_radius,
                            Eigen::Index self) const override {
    FirstOtherPoint result(squared_radius, self);
    index_.findNeighbors(result, query, nanoflann::SearchParams());
    return result.found();
  }
  const std::vector<Eigen::Index>& order() const override { return index_.vAcc; }

 private:
  using Index =
      nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, CoordinatesAdaptor>,
                                          CoordinatesAdaptor, D, Eigen::Index>;
  CoordinatesAdaptor adaptor_;
  Index index_;
};

PointSearch::PointSearch(const Eigen::MatrixXd& points) : coordinates_(points.transpose()) {
  switch (points.cols()) {
    case 1:
      tree_ = std::make_unique<FixedTree<1>>(coordinates_);
      break;
    case 2:
      tree_ = std::make_unique<FixedTree<2>>(coordinates_);
      break;
    case 3:
      tree_ = std::make_unique<FixedTree<3>>(coordinates_);
      break;
    default:
      throw std::invalid_argument("PointSearch: points must have 1, 2 or 3 coordinates, got " +
                                  std::to_string(points.cols()));
  }
}

PointSearch::~PointSearch() = default;
PointSearch::PointSearch(PointSearch&&) noexcept = default;
PointSearch& PointSearch::operator=(PointSearch&&) noexcept = default;

void PointSearch::nearest(const double* query, int k, Neighbours& found) const {
  const auto wanted = static_cast<std::size_t>(std::clamp<Eigen::Index>(k, 0, size()));
  found.indices.resize(wanted);
  found.squared_distances.resize(wanted);
  if (wanted == 0) return;
  const std::size_t count =
      tree_->nearest(query, wanted, found.indices.data(), found.squared_distances.data());
  found.indices.resize(count);
  found.squared_distances.resize(count);
}

PointSearch::Neighbours PointSearch::nearest(const double* query, int k) const {
  Neighbours found;
  nearest(query, k, found);
  return found;
}

void PointSearch::within(const double* query, double radius, Neighbours& found) const {
  thread_local std::vector<std::pair<Eigen::Index, double>> pairs;
  pairs.clear();
  tree_->within(query, radius * radius, pairs);
  found.indices.resize(pairs.size());
  found.squared_distances.resize(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    found.indices[i] = pairs[i].first;
    found.squared_distances[i] = pairs[i].second;
  }
}

const std::vector<Eigen::Index>& PointSearch::spatial_order() const {
  return tree_->order();
}

std::optional<std::pair<Eigen::Index, Eigen::Index>> PointSearch::find_coincident(
    double tolerance) const {
  // nanoflann keeps points strictly inside the radius: the smallest positive radius still
  // catches exact duplicates when the tolerance is zero.
  const double squared_radius = std::max(tolerance * tolerance, std::numeric_limits<double>::min());
  for (const Eigen::Index i : spatial_order()) {
    const Eigen::Index other = tree_->other_within(point(i), squared_radius, i);
    if (other >= 0) return std::make_pair(std::min(i, other), std::max(i, other));
  }
  return std::nullopt;
}

}  // namespace cocopp
