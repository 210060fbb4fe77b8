#pragma once
// A banded matrix with an in-place LU factorisation with partial pivoting (the LAPACK gbtrf
// scheme). The tube solvers' matrices have a few sub- and super-diagonals only: factoring the
// band costs O(n kl (kl + ku)) instead of O(n^3) for a dense LU.
#include <Eigen/Dense>
#include <vector>

namespace cocopp::tube {

class BandedMatrix {
 public:
  /// An n x n zero matrix with `lower` sub-diagonals and `upper` super-diagonals.
  BandedMatrix(int size, int lower, int upper);

  int size() const { return size_; }
  int lower() const { return lower_; }
  int upper() const { return upper_; }

  /// Entry (row, column); both must lie inside the band (std::out_of_range otherwise). Inline:
  /// the flow solver assembles its Jacobian through it, 3600 entries a solve.
  double& operator()(int row, int column) {
    if (!in_band(row, column)) throw_outside_band(row, column);
    return storage(row, column);
  }
  double operator()(int row, int column) const {
    return in_band(row, column) ? storage(row, column) : 0.0;
  }
  /// True if (row, column) lies inside the band given at construction.
  bool in_band(int row, int column) const {
    return row >= 0 && row < size_ && column >= 0 && column < size_ && column - row <= upper_ &&
           row - column <= lower_;
  }

  Eigen::MatrixXd to_dense() const;
  Eigen::VectorXd multiply(const Eigen::VectorXd& x) const;

 private:
  friend class BandedLu;
  // Row-major storage, each row wide enough for the fill-in that row swaps cause (`lower`
  // extra super-diagonals): entry (i, j) lives at i * width_ + (j - i + lower_).
  double& storage(int row, int column) { return values_[index(row, column)]; }
  double storage(int row, int column) const { return values_[index(row, column)]; }
  std::size_t index(int row, int column) const {
    return static_cast<std::size_t>(row) * static_cast<std::size_t>(width_) +
           static_cast<std::size_t>(column - row + lower_);
  }
  [[noreturn]] static void throw_outside_band(int row, int column);

  int size_;
  int lower_;
  int upper_;
  int width_;
  std::vector<double> values_;
};

/// LU factorisation with partial pivoting of a banded matrix, P A = L U.
class BandedLu {
 public:
  BandedLu() = default;
  /// Throws std::runtime_error if the matrix is singular.
  explicit BandedLu(BandedMatrix matrix);

  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;
  bool empty() const { return pivots_.empty(); }

 private:
  void factor();

  BandedMatrix lu_{0, 0, 0};         ///< U in the band (with fill-in)
  std::vector<double> multipliers_;  ///< L: `lower` multipliers per elimination step
  std::vector<int> pivots_;          ///< row swapped with row k at step k
};

/// Solve A x = b for a banded A (factor and solve once).
Eigen::VectorXd solve_banded(BandedMatrix matrix, const Eigen::VectorXd& rhs);

}  // namespace cocopp::tube
