#pragma once
// out += sum_j c_j column(j) for many long columns, as the secant models need (W c, V c, B y).
//
// On a 1e5-value interface with 100 columns this is memory-bound: every column must stream
// through once. Row block by row block, four columns at a time, the partial sum stays in the
// first-level cache and is read and written once per four columns: 2 to 3 times faster than
// one axpy per column or Eigen's column-major matrix-vector product without AVX.
#include <Eigen/Core>
#include <algorithm>

namespace cocopp {

/// `column(j)` returns column j (an Eigen vector expression of out.size() values).
template <class Column>
void add_linear_combination(Eigen::VectorXd& out, const Eigen::VectorXd& c, Column column) {
  constexpr Eigen::Index block = 2048;
  const Eigen::Index n = out.size(), count = c.size();
  for (Eigen::Index start = 0; start < n; start += block) {
    const Eigen::Index length = std::min(block, n - start);
    auto part = out.segment(start, length);
    auto piece = [&](Eigen::Index j) { return column(j).segment(start, length); };
    Eigen::Index j = 0;
    for (; j + 4 <= count; j += 4)
      part += c(j) * piece(j) + c(j + 1) * piece(j + 1) + c(j + 2) * piece(j + 2) +
              c(j + 3) * piece(j + 3);
    for (; j < count; ++j) part += c(j) * piece(j);
  }
}

}  // namespace cocopp
