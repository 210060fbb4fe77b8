#pragma once
// Thin QR factorization V = Q R of a tall matrix whose columns are inserted at the front
// (newest first) and removed anywhere, as the least-squares secant models need.
//
// Updates cost O(n k) (Givens rotations) instead of the O(n k^2) of a new factorization, which
// matters because a quasi-Newton model changes V in every coupling iteration.
#include <Eigen/Core>
#include <deque>

namespace cocopp {

class QrFactorization {
 public:
  Eigen::Index columns() const { return static_cast<Eigen::Index>(q_.size()); }
  void clear();

  /// V <- [v V]. Returns false (and changes nothing) if v lies numerically in the span of the
  /// current columns, where no update is accurate: the caller then factorizes anew.
  bool insert_front(const Eigen::VectorXd& v);
  /// V <- [V v] (v becomes the last, oldest column). Same return value as insert_front.
  bool append(const Eigen::VectorXd& v);
  /// Remove column j of V.
  void remove(Eigen::Index j);
  /// Remove the last (oldest) column of V.
  void remove_last();

  /// |R_jj|: the part of column j not in the span of the columns before it.
  double diagonal(Eigen::Index j) const { return std::abs(r_(j, j)); }
  /// c = argmin ||V c - b||.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;

 private:
  /// Split v into its coefficients on Q (w) and the orthogonal rest. Returns false if the rest
  /// is numerically zero.
  bool orthogonalize(const Eigen::VectorXd& v, Eigen::VectorXd& w, Eigen::VectorXd& rest) const;
  /// Apply the rotation [c s; -s c] to columns i and i + 1 of Q (and rows i, i+1 of R from
  /// column `from` on), so that R = Q^T V stays consistent.
  void rotate(Eigen::Index i, double c, double s, Eigen::Index from);

  std::deque<Eigen::VectorXd> q_;  ///< orthonormal columns; a deque makes front insertion O(1)
  Eigen::MatrixXd r_;              ///< columns() x columns(), upper triangular
};

}  // namespace cocopp
