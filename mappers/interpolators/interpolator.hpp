#pragma once
// Interpolators: linear operators that carry point values from one set of points (the source)
// to another (the target), built from the coordinates of both.
//
//   consistent mapping  target = M source      (displacement, pressure, traction)
//   conservative        source = M^T target    (nodal forces: totals preserved)
//
// The base class reads the settings every interpolator shares, selects the coordinate
// directions, checks the point sets and handles target points that have no partner; a concrete
// interpolator only builds its operator from the selected coordinates.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>
#include <string>
#include <vector>

#include "core/case/registry.hpp"
#include "core/data/interface.hpp"
#include "core/data/model_part.hpp"
#include "mappers/interpolators/point_search.hpp"

namespace cocopp {

/// Distances from each target point to its source stencil, for the mapping quality report.
struct MappingQuality {
  double min_distance = 0.0;
  double mean_distance = 0.0;
  double max_distance = 0.0;
  int fallbacks = 0;  ///< targets that used a documented fallback (e.g. linear -> nearest)
  int unmatched = 0;  ///< targets farther than `max_distance` from the source points
};

class Interpolator {
 public:
  static constexpr const char* kind = "mapper";
  /// Shared keys: `directions` (list of x, y, z; default all three), `max_distance` (a target
  /// farther than this from the source points has no partner; default: no limit),
  /// `unmatched` (zero | nearest | error, default zero: what an unmatched target gets).
  explicit Interpolator(const Settings& settings);
  virtual ~Interpolator() = default;

  /// Build the operator from `source` to `target` points (rows x y z). Throws
  /// std::invalid_argument for duplicate points, empty sets, bounding boxes that do not
  /// overlap, degenerate geometry, or unmatched points when `unmatched: error`.
  void initialize(const Coordinates& source, const Coordinates& target);

  /// Consistent mapping: values at the target points (rows) from values at the source points.
  RowMatrix map(const RowMatrix& source_values) const;
  /// Conservative mapping: M^T applied to values at the target points.
  RowMatrix map_transpose(const RowMatrix& target_values) const;

  const MappingQuality& quality() const { return quality_; }
  /// Per target point, the distance to its source stencil (infinite for an unmatched target):
  /// how well the source covers each target (a solver group gives each point to the member
  /// that covers it best).
  const Eigen::VectorXd& target_distances() const { return target_distances_; }
  Eigen::Index source_size() const { return source_size_; }
  Eigen::Index target_size() const { return target_size_; }

 protected:
  /// Build the sparse operator (target rows x source columns) from points with only the
  /// selected directions (n x d, d = 1..3), filling quality_ (distances, fallbacks).
  /// Interpolators that are not a plain sparse matrix override apply/apply_transpose too.
  virtual void build(const Eigen::MatrixXd& source, const Eigen::MatrixXd& target) = 0;
  virtual RowMatrix apply(const RowMatrix& source_values) const;
  virtual RowMatrix apply_transpose(const RowMatrix& target_values) const;

  /// The k-d tree over the source points (selected directions), built once per initialize.
  const PointSearch& source_search() const { return *source_search_; }
  /// Target indices in a spatially coherent order: build loops that follow it find their
  /// neighbours in the cache (several times faster on large random point sets).
  const std::vector<Eigen::Index>& target_order() const { return target_search_->spatial_order(); }
  /// Fill the distance fields of quality_ from one stencil distance per target point.
  void record_distances(const Eigen::VectorXd& distances);

  Eigen::SparseMatrix<double, Eigen::RowMajor> matrix_;
  MappingQuality quality_;

 private:
  Eigen::VectorXd target_distances_;
  Eigen::MatrixXd select_directions(const Coordinates& points) const;
  std::string direction_names() const;
  void check_not_empty(const Coordinates& points, const std::string& name) const;
  void check_no_duplicates(const PointSearch& search, const Eigen::MatrixXd& selected,
                           const Coordinates& points, const std::string& name) const;
  void check_boxes_overlap(const Eigen::MatrixXd& source, const Eigen::MatrixXd& target) const;
  void treat_unmatched(const Eigen::MatrixXd& source, const Eigen::MatrixXd& target);
  void check_initialized() const;

  std::unique_ptr<PointSearch> source_search_;
  std::unique_ptr<PointSearch> target_search_;  ///< for the checks and target_order()

  enum class Unmatched { kZero, kNearest, kError };

  std::vector<int> directions_;  ///< 0 = x, 1 = y, 2 = z
  double max_distance_;
  Unmatched unmatched_;
  std::vector<Eigen::Index> unmatched_targets_;
  std::vector<Eigen::Index> unmatched_nearest_sources_;  ///< per unmatched target
  Eigen::Index source_size_ = 0, target_size_ = 0;
};

using InterpolatorRegistry = Registry<Interpolator>;

}  // namespace cocopp
