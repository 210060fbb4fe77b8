#pragma once
// SparseRows: assembles a row-major sparse matrix row by row, straight into compressed storage
// (no triplets, no sorting): interpolators produce their rows in target order.
#include <Eigen/SparseCore>
#include <vector>

namespace cocopp {

class SparseRows {
 public:
  using Matrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  using StorageIndex = Matrix::StorageIndex;

  SparseRows(Eigen::Index rows, Eigen::Index cols, std::size_t expected_per_row)
      : rows_(rows), cols_(cols) {
    outer_.reserve(static_cast<std::size_t>(rows) + 1);
    outer_.push_back(0);
    inner_.reserve(static_cast<std::size_t>(rows) * expected_per_row);
    values_.reserve(static_cast<std::size_t>(rows) * expected_per_row);
  }

  /// Add one entry to the current row; columns need not be sorted but must be unique.
  void add(Eigen::Index col, double value) {
    inner_.push_back(static_cast<StorageIndex>(col));
    values_.push_back(value);
  }
  /// Close the current row and start the next one.
  void end_row() { outer_.push_back(static_cast<StorageIndex>(inner_.size())); }

  Eigen::Index rows_done() const { return static_cast<Eigen::Index>(outer_.size()) - 1; }

  /// The matrix; all `rows` rows must have been ended.
  Matrix finish() {
    sort_rows();
    const Eigen::Map<const Matrix> view(rows_, cols_, static_cast<Eigen::Index>(values_.size()),
                                        outer_.data(), inner_.data(), values_.data());
    return Matrix(view);
  }

 private:
  /// Eigen expects increasing columns within a row (binary searches in coeff()); rows are short,
  /// so insertion sort.
  void sort_rows() {
    for (std::size_t row = 0; row + 1 < outer_.size(); ++row) {
      const auto begin = static_cast<std::size_t>(outer_[row]);
      const auto end = static_cast<std::size_t>(outer_[row + 1]);
      for (std::size_t i = begin + 1; i < end; ++i) {
        const StorageIndex col = inner_[i];
        const double value = values_[i];
        std::size_t j = i;
        for (; j > begin && inner_[j - 1] > col; --j) {
          inner_[j] = inner_[j - 1];
          values_[j] = values_[j - 1];
        }
        inner_[j] = col;
        values_[j] = value;
      }
    }
  }

  Eigen::Index rows_, cols_;
  std::vector<StorageIndex> outer_, inner_;
  std::vector<double> values_;
};

}  // namespace cocopp
