// radial_basis: interpolation with the compactly supported Wendland C2 function
//   phi(r) = (1 - r/R)^4 (4 r/R + 1) for r < R, else 0,
// optionally augmented with a linear polynomial so that constant and linear fields are
// reproduced exactly:
//   [Phi P; P^T 0] [a; b] = [f; 0],   target values = [Phi_ts P_t] [a; b].
// Both the system matrix K and the evaluation matrix E are sparse (only pairs within R), K is
// factorized once in build; map() is E K^-1 [f; 0], map_transpose() its exact transpose
// [I 0] K^-T E^T g (K is symmetric, so the same factorization serves both).
#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "mappers/interpolators/interpolator.hpp"
#include "mappers/interpolators/sparse_rows.hpp"

namespace cocopp {
namespace {

double wendland_c2(double r_over_support) {
  if (r_over_support >= 1.0) return 0.0;
  const double s = 1.0 - r_over_support;
  return s * s * s * s * (4.0 * r_over_support + 1.0);
}

/// Linear polynomial basis 1, q_1 .. q_m of the source points: q are coordinates along the
/// principal directions that the source points actually span, so that points on a plane in 3D
/// (or on a line) do not make the augmented system singular.
class LinearBasis {
 public:
  explicit LinearBasis(const Eigen::MatrixXd& source) {
    center_ = source.colwise().mean();
    const Eigen::MatrixXd centered = source.rowwise() - center_;
    scale_ = centered.cwiseAbs().maxCoeff();
    if (!(scale_ > 0.0)) scale_ = 1.0;
    const Eigen::MatrixXd covariance =
        (centered / scale_).transpose() * (centered / scale_) / double(source.rows());
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(covariance);
    const double largest = eigen.eigenvalues().maxCoeff();
    std::vector<Eigen::Index> spanned;
    for (Eigen::Index k = 0; k < eigen.eigenvalues().size(); ++k)
      if (eigen.eigenvalues()(k) > 1e-10 * largest) spanned.push_back(k);
    directions_.resize(source.cols(), static_cast<Eigen::Index>(spanned.size()));
    for (std::size_t k = 0; k < spanned.size(); ++k)
      directions_.col(static_cast<Eigen::Index>(k)) = eigen.eigenvectors().col(spanned[k]);
  }
  /// Number of basis functions (1 + spanned directions).
  Eigen::Index size() const { return 1 + directions_.cols(); }
  /// The basis at `point` (a row of d coordinates).
  Eigen::RowVectorXd at(const Eigen::RowVectorXd& point) const {
    Eigen::RowVectorXd values(size());
    values(0) = 1.0;
    values.tail(directions_.cols()) = ((point - center_) / scale_) * directions_;
    return values;
  }

 private:
  Eigen::RowVectorXd center_;
  double scale_ = 1.0;
  Eigen::MatrixXd directions_;  ///< d x m, orthonormal columns
};

class RadialBasis : public Interpolator {
 public:
  explicit RadialBasis(const Settings& settings)
      : Interpolator(settings),
        support_radius_(settings.required_in_range("support_radius", Range::positive())),
        polynomial_(settings.get<bool>("polynomial", true)) {}

 protected:
  void build(const Eigen::MatrixXd& source, const Eigen::MatrixXd& target) override {
    const Eigen::Index n = source.rows();
    std::optional<LinearBasis> basis;
    if (polynomial_) basis.emplace(source);
    augmented_size_ = n + (basis ? basis->size() : 0);
    factorize(system_matrix(source, basis));
    evaluation_ = evaluation_matrix(target, basis);
  }

  RowMatrix apply(const RowMatrix& source_values) const override {
    Eigen::MatrixXd right_side = Eigen::MatrixXd::Zero(augmented_size_, source_values.cols());
    right_side.topRows(source_values.rows()) = source_values;
    const Eigen::MatrixXd coefficients = solve(right_side);
    return evaluation_ * coefficients;
  }

  RowMatrix apply_transpose(const RowMatrix& target_values) const override {
    const Eigen::MatrixXd spread = evaluation_.transpose() * target_values;
    return solve(spread).topRows(source_size_of_system());
  }

 private:
  Eigen::Index source_size_of_system() const { return augmented_size_ - polynomial_size_; }

  /// K = [Phi P; P^T 0] (or Phi alone), column-major for the sparse solvers.
  Eigen::SparseMatrix<double> system_matrix(const Eigen::MatrixXd& source,
                                            const std::optional<LinearBasis>& basis) {
    const Eigen::Index n = source.rows();
    polynomial_size_ = basis ? basis->size() : 0;
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(static_cast<std::size_t>(n) * (16 + 2 * polynomial_size_));
    PointSearch::Neighbours found;
    for (Eigen::Index i = 0; i < n; ++i) {
      source_search().within(source_search().point(i), support_radius_, found);
      if (found.size() < 2) fail_no_neighbour(source, i);
      for (std::size_t k = 0; k < found.size(); ++k)
        entries.emplace_back(i, found.indices[k],
                             wendland_c2(std::sqrt(found.squared_distances[k]) / support_radius_));
      if (!basis) continue;
      const Eigen::RowVectorXd p = basis->at(source.row(i));
      for (Eigen::Index j = 0; j < p.size(); ++j) {
        entries.emplace_back(i, n + j, p(j));
        entries.emplace_back(n + j, i, p(j));
      }
    }
    Eigen::SparseMatrix<double> matrix(augmented_size_, augmented_size_);
    matrix.setFromTriplets(entries.begin(), entries.end());
    return matrix;
  }

  [[noreturn]] void fail_no_neighbour(const Eigen::MatrixXd& source, Eigen::Index i) const {
    const auto nearest = source_search().nearest(source_search().point(i), 2);
    const double distance = nearest.size() < 2 ? 0.0 : std::sqrt(nearest.squared_distances.back());
    std::string where;
    for (Eigen::Index c = 0; c < source.cols(); ++c)
      where += fmt::format("{}{:g}", c == 0 ? "(" : ", ", source(i, c));
    throw std::invalid_argument(fmt::format(
        "radial_basis: support_radius {:g} too small: source point {} {}) has no neighbour "
        "within R (its nearest neighbour is at {:g}); use a radius of a few point spacings",
        support_radius_, i, where, distance));
  }

  /// Wendland C2 on the plain system is positive definite (LDL^T); the augmented system is a
  /// symmetric saddle point, indefinite (LU).
  void factorize(const Eigen::SparseMatrix<double>& matrix) {
    bool ok = false;
    if (polynomial_size_ == 0) {
      cholesky_.compute(matrix);
      ok = cholesky_.info() == Eigen::Success;
    } else {
      lu_.analyzePattern(matrix);
      lu_.factorize(matrix);
      ok = lu_.info() == Eigen::Success;
    }
    if (!ok)
      throw std::invalid_argument(fmt::format(
          "radial_basis: the interpolation system of {} source points is singular (support "
          "radius {:g}{}); too few points for the polynomial, or points on a line in 2D/3D?",
          source_size_of_system(), support_radius_, polynomial_ ? ", linear polynomial" : ""));
  }

  Eigen::MatrixXd solve(const Eigen::MatrixXd& right_side) const {
    if (polynomial_size_ == 0) return cholesky_.solve(right_side);
    // SparseLU::solve is not const in Eigen 3.4 (it works on internal buffers).
    return const_cast<Eigen::SparseLU<Eigen::SparseMatrix<double>>&>(lu_).solve(right_side);
  }

  /// E = [Phi_ts P_t]: rows for the targets, columns for the augmented unknowns.
  Eigen::SparseMatrix<double, Eigen::RowMajor> evaluation_matrix(
      const Eigen::MatrixXd& target, const std::optional<LinearBasis>& basis) {
    const Eigen::Index n = source_size_of_system();
    SparseRows rows(target.rows(), augmented_size_,
                    16 + static_cast<std::size_t>(polynomial_size_));
    Eigen::VectorXd distances(target.rows());
    PointSearch::Neighbours found;
    Eigen::RowVectorXd query(target.cols());
    for (Eigen::Index t = 0; t < target.rows(); ++t) {
      query = target.row(t);
      source_search().within(query.data(), support_radius_, found);
      double nearest2 = std::numeric_limits<double>::infinity();
      for (std::size_t k = 0; k < found.size(); ++k) {
        nearest2 = std::min(nearest2, found.squared_distances[k]);
        rows.add(found.indices[k],
                 wendland_c2(std::sqrt(found.squared_distances[k]) / support_radius_));
      }
      if (basis) {
        const Eigen::RowVectorXd p = basis->at(query);
        for (Eigen::Index j = 0; j < p.size(); ++j) rows.add(n + j, p(j));
      }
      rows.end_row();
      if (found.size() == 0) {  // outside every support: polynomial part only (or zero)
        ++quality_.fallbacks;
        nearest2 = source_search().nearest(query.data(), 1).squared_distances[0];
      }
      distances(t) = std::sqrt(nearest2);
    }
    record_distances(distances);
    return rows.finish();
  }

  double support_radius_;
  bool polynomial_;
  Eigen::Index augmented_size_ = 0;
  Eigen::Index polynomial_size_ = 0;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> cholesky_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> evaluation_;
};

}  // namespace

COCOPP_REGISTER(InterpolatorRegistry, "radial_basis", RadialBasis)

}  // namespace cocopp
