// linear: piecewise-linear interpolation on a stencil of nearby source points, chosen per target
// from the k-d tree without a mesh:
//   1D  the two source points that bracket the target;
//   2D  the segment from the nearest source point to one of its neighbours that contains the
//       target's projection (points on a curve);
//   3D  the triangle of nearby source points that contains the target's projection (points on
//       a surface).
// Nothing is extrapolated: a target outside every candidate segment or triangle falls back to a
// segment (3D) or to the nearest source point, and is counted in quality().fallbacks.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

#include "mappers/interpolators/interpolator.hpp"
#include "mappers/interpolators/parallel.hpp"
#include "mappers/interpolators/sparse_rows.hpp"

namespace cocopp {
namespace {

/// Up to three source points with their weights.
struct Stencil {
  std::array<Eigen::Index, 3> sources{};
  std::array<double, 3> weights{};
  std::array<int, 3> slots{};  ///< positions among the candidates (2D, 3D)
  int size = 0;
  bool fallback = false;
  double distance = 0.0;  ///< from the target to its projection on the stencil

  static Stencil single(Eigen::Index source, bool fallback, double distance = 0.0) {
    Stencil s;
    s.sources[0] = source;
    s.weights[0] = 1.0;
    s.size = 1;
    s.fallback = fallback;
    s.distance = distance;
    return s;
  }
};

/// A projection parameter or barycentric weight counts as inside its segment or triangle up to
/// this round-off margin (targets exactly on an edge must not fall back).
constexpr double kInsideTolerance = 1e-10;
/// Triangles whose angle at a vertex has sin^2 below this are treated as collinear: their
/// barycentric weights would be dominated by round-off.
constexpr double kCollinearSin2 = 1e-10;
/// Candidates searched around a target: enough for a full ring of neighbours on a surface.
constexpr int kCurveCandidates = 6;
constexpr int kSurfaceCandidates = 10;
constexpr int kWideCandidates = 24;

/// Candidate source points around one target, as vectors from the nearest one (p0), with
/// their inner products: every segment and triangle test is then a few flops.
class CandidateGeometry {
 public:
  /// Gram matrix and target products of candidates `found` around `target` (d coordinates).
  void set(const PointSearch& search, const PointSearch::Neighbours& found, const double* target) {
    count_ = static_cast<int>(found.size());
    const int d = search.dimension();
    const double* p0 = search.point(found.indices[0]);
    for (int i = 0; i < count_; ++i) {
      const double* p = search.point(found.indices[static_cast<std::size_t>(i)]);
      for (int c = 0; c < d; ++c) edge_[i][c] = p[c] - p0[c];
    }
    for (int c = 0; c < d; ++c) offset_[c] = target[c] - p0[c];
    dimension_ = d;
    offset_norm2_ = dot(offset_, offset_, d);
    computed_ = 0;
    compute_products(std::min(count_, 3));  // enough for the usual first try
  }
  int count() const { return count_; }
  /// Make all candidates available to the projections (only the first three are by default).
  void use_all() { compute_products(count_); }

  /// Distance from the target to sum_k weights[k] * candidate slots[k] (the weights sum to 1),
  /// from the local edge vectors: no cancellation for targets close to the stencil.
  double distance(const Stencil& stencil) const {
    double squared = 0.0;
    for (int c = 0; c < dimension_; ++c) {
      double gap = offset_[c];
      for (int k = 0; k < stencil.size; ++k) gap -= stencil.weights[k] * edge_[stencil.slots[k]][c];
      squared += gap * gap;
    }
    return std::sqrt(squared);
  }

  /// Projection of the target on segment (a, b): parameter t along a -> b and squared distance
  /// from the target to the projection. False for a zero-length segment.
  bool project_on_segment(int a, int b, double& t, double& squared_distance) const {
    const double length2 = gram_[b][b] - 2.0 * gram_[a][b] + gram_[a][a];
    if (!(length2 > 0.0)) return false;
    const double along = target_dot_[b] - target_dot_[a] - gram_[a][b] + gram_[a][a];
    t = along / length2;
    squared_distance = offset_squared(a) - t * along;
    return true;
  }

  /// Projection of the target on the plane of triangle (a, b, c): barycentric weights of b and
  /// c (u, v) and squared distance. False for a (nearly) collinear triangle.
  bool project_on_triangle(int a, int b, int c, double& u, double& v,
                           double& squared_distance) const {
    const double g11 = gram_[b][b] - 2.0 * gram_[a][b] + gram_[a][a];
    const double g22 = gram_[c][c] - 2.0 * gram_[a][c] + gram_[a][a];
    const double g12 = gram_[b][c] - gram_[a][b] - gram_[a][c] + gram_[a][a];
    const double det = g11 * g22 - g12 * g12;
    if (!(det > kCollinearSin2 * g11 * g22)) return false;
    const double r1 = target_dot_[b] - target_dot_[a] - gram_[a][b] + gram_[a][a];
    const double r2 = target_dot_[c] - target_dot_[a] - gram_[a][c] + gram_[a][a];
    u = (g22 * r1 - g12 * r2) / det;
    v = (g11 * r2 - g12 * r1) / det;
    squared_distance = offset_squared(a) - (u * r1 + v * r2);
    return true;
  }

 private:
  void compute_products(int upto) {
    for (int i = computed_; i < upto; ++i) {
      for (int j = 0; j <= i; ++j) gram_[i][j] = gram_[j][i] = dot(edge_[i], edge_[j], dimension_);
      target_dot_[i] = dot(offset_, edge_[i], dimension_);
    }
    computed_ = std::max(computed_, upto);
  }

  static double dot(const double* x, const double* y, int d) {
    double sum = 0.0;
    for (int c = 0; c < d; ++c) sum += x[c] * y[c];
    return sum;
  }
  /// |target - p_a|^2
  double offset_squared(int a) const { return offset_norm2_ - 2.0 * target_dot_[a] + gram_[a][a]; }

  int count_ = 0;
  int computed_ = 0;  ///< candidates with their inner products computed
  int dimension_ = 3;
  double edge_[kWideCandidates][3] = {};
  double offset_[3] = {};
  double offset_norm2_ = 0.0;
  double gram_[kWideCandidates][kWideCandidates] = {};
  double target_dot_[kWideCandidates] = {};
};

bool inside_segment(double t) {
  return t >= -kInsideTolerance && t <= 1.0 + kInsideTolerance;
}
bool inside_triangle(double u, double v) {
  return u >= -kInsideTolerance && v >= -kInsideTolerance && u + v <= 1.0 + kInsideTolerance;
}

/// Finds the stencil of one target at a time. It holds the per-target work space (so a loop
/// over many targets allocates once), so every thread of a build has its own.
class StencilFinder {
 public:
  /// `order` and `sorted` are the 1D sources sorted by coordinate (empty in 2D and 3D).
  StencilFinder(const PointSearch& search, const std::vector<Eigen::Index>& order,
                const std::vector<double>& sorted)
      : search_(search), order_(order), sorted_(sorted) {}

  Stencil find(const double* x) {
    switch (search_.dimension()) {
      case 1:
        return bracket(x[0]);
      case 2:
        return on_curve(x);
      default:
        return on_surface(x);
    }
  }

 private:
  /// 1D: the two source points on either side; outside the source range, the end point.
  Stencil bracket(double x) const {
    if (x <= sorted_.front())
      return Stencil::single(order_.front(), x < sorted_.front(), sorted_.front() - x);
    if (x >= sorted_.back())
      return Stencil::single(order_.back(), x > sorted_.back(), x - sorted_.back());
    const auto right = static_cast<std::size_t>(
        std::upper_bound(sorted_.begin(), sorted_.end(), x) - sorted_.begin());
    const double t = (x - sorted_[right - 1]) / (sorted_[right] - sorted_[right - 1]);
    Stencil s;
    s.sources = {order_[right - 1], order_[right], 0};
    s.weights = {1.0 - t, t, 0.0};
    s.size = 2;
    return s;
  }

  /// 2D: the segment from the nearest source point to a neighbour that contains the target's
  /// projection, the closest such segment if several do; else the nearest source point.
  Stencil on_curve(const double* x) {
    search_.nearest(x, kCurveCandidates, found_);
    geometry_.set(search_, found_, x);
    geometry_.use_all();
    Stencil best = Stencil::single(found_.indices[0], true);
    best_squared_distance_ = std::numeric_limits<double>::infinity();
    try_segments(best);
    return with_distance(best);
  }

  /// 3D: the triangle of the three nearest source points if it contains the target's
  /// projection; else the closest containing triangle with the nearest point as a vertex;
  /// else with any three of the candidates; else the closest containing triangle around the
  /// nearest point among more candidates (near the edge of a random point cloud the nearest
  /// ones may all lie on one side); else (fallback) the closest segment from the nearest point;
  /// else (fallback) the nearest point.
  Stencil on_surface(const double* x) {
    search_.nearest(x, kSurfaceCandidates, found_);
    geometry_.set(search_, found_, x);
    Stencil best = Stencil::single(found_.indices[0], true);
    best_squared_distance_ = std::numeric_limits<double>::infinity();
    const int n = geometry_.count();
    if (n >= 3 && try_triangle(0, 1, 2, best)) return with_distance(best);
    geometry_.use_all();
    try_fan(best);
    if (best.size == 3) return with_distance(best);
    for (int i = 1; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        for (int k = j + 1; k < n; ++k) try_triangle(i, j, k, best);
    if (best.size == 3) return with_distance(best);
    if (search_.size() > kSurfaceCandidates) {
      search_.nearest(x, kWideCandidates, found_);
      geometry_.set(search_, found_, x);
      geometry_.use_all();
      try_fan(best);
      if (best.size == 3) return with_distance(best);
    }
    try_segments(best);
    return with_distance(best);
  }

  Stencil with_distance(Stencil stencil) const {
    stencil.distance = geometry_.distance(stencil);
    return stencil;
  }

  /// Triangles with the nearest candidate as a vertex.
  void try_fan(Stencil& best) {
    for (int i = 1; i < geometry_.count(); ++i)
      for (int j = i + 1; j < geometry_.count(); ++j) try_triangle(0, i, j, best);
  }

  /// Replace `best` by triangle (a, b, c) of the candidates if it contains the projection and
  /// is closer. True when it did.
  bool try_triangle(int a, int b, int c, Stencil& best) {
    double u = 0.0, v = 0.0, squared_distance = 0.0;
    if (!geometry_.project_on_triangle(a, b, c, u, v, squared_distance)) return false;
    if (!inside_triangle(u, v) || !(squared_distance < best_squared_distance_)) return false;
    best_squared_distance_ = squared_distance;
    best.sources = {candidate(a), candidate(b), candidate(c)};
    best.slots = {a, b, c};
    best.weights = {1.0 - u - v, u, v};
    best.size = 3;
    best.fallback = false;
    return true;
  }

  /// Segments from the nearest candidate; a segment is a fallback on a surface, not on a curve.
  void try_segments(Stencil& best) {
    const bool fallback = search_.dimension() == 3;
    for (int j = 1; j < geometry_.count(); ++j) {
      double t = 0.0, squared_distance = 0.0;
      if (!geometry_.project_on_segment(0, j, t, squared_distance)) continue;
      if (!inside_segment(t) || !(squared_distance < best_squared_distance_)) continue;
      best_squared_distance_ = squared_distance;
      best.sources = {candidate(0), candidate(j), 0};
      best.slots = {0, j, 0};
      best.weights = {1.0 - t, t, 0.0};
      best.size = 2;
      best.fallback = fallback;
    }
  }

  Eigen::Index candidate(int i) const { return found_.indices[static_cast<std::size_t>(i)]; }

  const PointSearch& search_;
  const std::vector<Eigen::Index>& order_;
  const std::vector<double>& sorted_;
  PointSearch::Neighbours found_;
  CandidateGeometry geometry_;
  double best_squared_distance_ = 0.0;
};

class Linear : public Interpolator {
 public:
  using Interpolator::Interpolator;

 protected:
  void build(const Eigen::MatrixXd& source, const Eigen::MatrixXd& target) override {
    if (source.cols() == 1) sort_sources(source);
    std::vector<Stencil> stencils(static_cast<std::size_t>(target.rows()));
    const std::vector<Eigen::Index>& order = target_order();
    // Targets in the tree's order, split into contiguous chunks: each thread stays in one
    // region of space (and of the cache).
    parallel_chunks(order.size(), [&](std::size_t begin, std::size_t end) {
      StencilFinder finder(source_search(), order_, sorted_);
      Eigen::RowVectorXd query(target.cols());
      for (std::size_t i = begin; i < end; ++i) {
        const Eigen::Index t = order[i];
        query = target.row(t);
        stencils[static_cast<std::size_t>(t)] = finder.find(query.data());
      }
    });
    assemble(stencils, source.rows());
  }

 private:
  /// The sparse matrix and the quality report, in target order.
  void assemble(const std::vector<Stencil>& stencils, Eigen::Index source_count) {
    const auto target_count = static_cast<Eigen::Index>(stencils.size());
    SparseRows rows(target_count, source_count, 3);
    Eigen::VectorXd distances(target_count);
    for (Eigen::Index t = 0; t < target_count; ++t) {
      const Stencil& stencil = stencils[static_cast<std::size_t>(t)];
      for (int k = 0; k < stencil.size; ++k) rows.add(stencil.sources[k], stencil.weights[k]);
      rows.end_row();
      distances(t) = stencil.distance;
      if (stencil.fallback) ++quality_.fallbacks;
    }
    matrix_ = rows.finish();
    record_distances(distances);
  }

  void sort_sources(const Eigen::MatrixXd& source) {
    order_.resize(static_cast<std::size_t>(source.rows()));
    std::iota(order_.begin(), order_.end(), Eigen::Index{0});
    std::sort(order_.begin(), order_.end(),
              [&](Eigen::Index a, Eigen::Index b) { return source(a, 0) < source(b, 0); });
    sorted_.resize(order_.size());
    for (std::size_t i = 0; i < order_.size(); ++i) sorted_[i] = source(order_[i], 0);
  }

  // 1D: source indices sorted by coordinate, and the sorted coordinates.
  std::vector<Eigen::Index> order_;
  std::vector<double> sorted_;
};

}  // namespace

COCOPP_REGISTER(InterpolatorRegistry, "linear", Linear)

}  // namespace cocopp
