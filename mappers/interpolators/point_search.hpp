#pragma once
// PointSearch: a k-d tree over a set of points (n x d, d = 1..3), the one place that talks to
// nanoflann. Every interpolator searches its source points through it.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace cocopp {

class PointSearch {
 public:
  /// Indices and squared distances of found points; reused between queries so that a loop
  /// over many query points allocates only once.
  struct Neighbours {
    std::vector<Eigen::Index> indices;
    std::vector<double> squared_distances;
    std::size_t size() const { return indices.size(); }
  };

  /// Index the rows of `points` (n x d, d = 1..3); the coordinates are copied.
  explicit PointSearch(const Eigen::MatrixXd& points);
  ~PointSearch();
  PointSearch(PointSearch&&) noexcept;
  PointSearch& operator=(PointSearch&&) noexcept;

  Eigen::Index size() const { return coordinates_.cols(); }
  int dimension() const { return static_cast<int>(coordinates_.rows()); }
  /// The d contiguous coordinates of point `i`.
  const double* point(Eigen::Index i) const { return coordinates_.col(i).data(); }

  /// The `k` points nearest to `query` (d coordinates), closest first; fewer when the set
  /// holds fewer points. Overwrites `found`.
  void nearest(const double* query, int k, Neighbours& found) const;
  Neighbours nearest(const double* query, int k) const;

  /// All points closer than `radius` to `query`, in no particular order. Overwrites `found`.
  void within(const double* query, double radius, Neighbours& found) const;

  /// All point indices in the order of the tree's leaves: neighbours in space are mostly
  /// neighbours in this order, so looping over points in it keeps the tree in the cache.
  const std::vector<Eigen::Index>& spatial_order() const;

  /// A pair of points (i < j) closer to each other than `tolerance` (or coincident when the
  /// tolerance is zero), if there is one.
  std::optional<std::pair<Eigen::Index, Eigen::Index>> find_coincident(double tolerance) const;

 private:
  class Tree;
  template <int D>
  class FixedTree;

  Eigen::MatrixXd coordinates_;  ///< d x n: each point's coordinates contiguous
  std::unique_ptr<Tree> tree_;
};

}  // namespace cocopp
