#include "solvers/tube/banded_solver.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace cocopp::tube {

namespace {

int checked_size(int value) {
  if (value < 0) throw std::invalid_argument("BandedMatrix: negative size or bandwidth");
  return value;
}

}  // namespace

BandedMatrix::BandedMatrix(int size, int lower, int upper)
    : size_(checked_size(size)),
      lower_(checked_size(lower)),
      upper_(checked_size(upper)),
      width_(2 * lower_ + upper_ + 1),
      values_(static_cast<std::size_t>(size_) * static_cast<std::size_t>(width_), 0.0) {}

void BandedMatrix::throw_outside_band(int row, int column) {
  throw std::out_of_range("BandedMatrix: entry (" + std::to_string(row) + ", " +
                          std::to_string(column) + ") outside the band");
}

Eigen::MatrixXd BandedMatrix::to_dense() const {
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(size_, size_);
  for (int i = 0; i < size_; ++i) {
    for (int j = std::max(0, i - lower_); j <= std::min(size_ - 1, i + upper_); ++j) {
      dense(i, j) = storage(i, j);
    }
  }
  return dense;
}

Eigen::VectorXd BandedMatrix::multiply(const Eigen::VectorXd& x) const {
  Eigen::VectorXd y = Eigen::VectorXd::Zero(size_);
  for (int i = 0; i < size_; ++i) {
    for (int j = std::max(0, i - lower_); j <= std::min(size_ - 1, i + upper_); ++j) {
      y[i] += storage(i, j) * x[j];
    }
  }
  return y;
}

BandedLu::BandedLu(BandedMatrix matrix) : lu_(std::move(matrix)) {
  factor();
}

void BandedLu::factor() {
  const int n = lu_.size_;
  const int lower = lu_.lower_;
  // After a swap, row k may reach `lower` columns further right than its original band.
  const int reach = lu_.lower_ + lu_.upper_;
  multipliers_.assign(static_cast<std::size_t>(n) * static_cast<std::size_t>(lower), 0.0);
  pivots_.assign(n, 0);
  for (int k = 0; k < n; ++k) {
    const int last_row = std::min(n - 1, k + lower);
    const int last_column = std::min(n - 1, k + reach);
    int pivot = k;
    for (int row = k + 1; row <= last_row; ++row) {
      if (std::abs(lu_.storage(row, k)) > std::abs(lu_.storage(pivot, k))) pivot = row;
    }
    if (lu_.storage(pivot, k) == 0.0) {
      throw std::runtime_error("banded LU: singular matrix (zero pivot in column " +
                               std::to_string(k) + ")");
    }
    pivots_[k] = pivot;
    if (pivot != k) {
      for (int column = k; column <= last_column; ++column) {
        std::swap(lu_.storage(k, column), lu_.storage(pivot, column));
      }
    }
    const double diagonal = lu_.storage(k, k);
    for (int row = k + 1; row <= last_row; ++row) {
      const double multiplier = lu_.storage(row, k) / diagonal;
      multipliers_[static_cast<std::size_t>(k) * lower + (row - k - 1)] = multiplier;
      lu_.storage(row, k) = 0.0;
      if (multiplier == 0.0) continue;
      for (int column = k + 1; column <= last_column; ++column) {
        lu_.storage(row, column) -= multiplier * lu_.storage(k, column);
      }
    }
  }
}

Eigen::VectorXd BandedLu::solve(const Eigen::VectorXd& rhs) const {
  const int n = lu_.size_;
  const int lower = lu_.lower_;
  const int reach = lu_.lower_ + lu_.upper_;
  if (rhs.size() != n) throw std::invalid_argument("banded LU: right-hand side size mismatch");
  Eigen::VectorXd x = rhs;
  // Forward: apply the row swaps and eliminations in the order they were made.
  for (int k = 0; k < n; ++k) {
    if (pivots_[k] != k) std::swap(x[k], x[pivots_[k]]);
    const int last_row = std::min(n - 1, k + lower);
    for (int row = k + 1; row <= last_row; ++row) {
      x[row] -= multipliers_[static_cast<std::size_t>(k) * lower + (row - k - 1)] * x[k];
    }
  }
  // Backward substitution with U (upper bandwidth lower + upper).
  for (int k = n - 1; k >= 0; --k) {
    double sum = x[k];
    const int last_column = std::min(n - 1, k + reach);
    for (int column = k + 1; column <= last_column; ++column) {
      sum -= lu_.storage(k, column) * x[column];
    }
    x[k] = sum / lu_.storage(k, k);
  }
  return x;
}

Eigen::VectorXd solve_banded(BandedMatrix matrix, const Eigen::VectorXd& rhs) {
  return BandedLu(std::move(matrix)).solve(rhs);  // a Jacobian just built: no copy
}

}  // namespace cocopp::tube
