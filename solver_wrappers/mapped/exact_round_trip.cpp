#include "solver_wrappers/mapped/exact_round_trip.hpp"

#include <algorithm>
#include <stdexcept>

namespace cocopp {

namespace {

/// A pivot of the factorisation counts from this fraction of the largest on: the round trip's
/// own singular values are interpolation weights (order 0.1 to 1); anything near round-off
/// is a direction that no node value reaches.
constexpr double kRankThreshold = 1e-9;

Eigen::VectorXd flatten(const RowMatrix& values) {
  return Eigen::Map<const Eigen::VectorXd>(values.data(), values.size());
}

double largest(const Eigen::VectorXd& values, const std::vector<Eigen::Index>& entries) {
  return Eigen::VectorXd(values(entries)).cwiseAbs().maxCoeff();
}

}  // namespace

void ExactRoundTrip::build(const Mapper& input, const std::vector<Eigen::Index>& rows,
                           const Mapper& output, Eigen::Index points, int components) {
  input_ = &input;
  output_ = &output;
  rows_ = rows;
  points_ = points;
  components_ = components;
  held_.assign(rows_.size(), false);
  factorised_ = false;  // in the first map(): the step's hold() usually comes first
}

void ExactRoundTrip::hold(const std::vector<bool>& held) {
  if (held.size() != rows_.size())
    throw std::invalid_argument("ExactRoundTrip::hold: one flag per inner output node expected");
  if (held == held_) return;
  held_ = held;
  factorised_ = false;
}

void ExactRoundTrip::factorise() {
  factorised_ = true;
  plain_defect_ = defect_ = 0.0;
  const Eigen::MatrixXd matrix = round_trip_matrix();
  // Only the entries the round trip reaches take part (a component that the output mapper
  // masks, points beyond the driven nodes' reach): the rest stays as w gives it.
  reached_rows_.clear();
  reached_columns_.clear();
  for (Eigen::Index i = 0; i < matrix.rows(); ++i)
    if (matrix.row(i).cwiseAbs().maxCoeff() > 0.0) reached_rows_.push_back(i);
  for (Eigen::Index j = 0; j < matrix.cols(); ++j)
    if (matrix.col(j).cwiseAbs().maxCoeff() > 0.0) reached_columns_.push_back(j);
  if (reached_rows_.empty()) return;  // all held: nothing to solve for
  solver_.setThreshold(kRankThreshold);
  solver_.compute(matrix(reached_rows_, reached_columns_));
}

RowMatrix ExactRoundTrip::to_inner(const Eigen::VectorXd& w) const {
  return input_->map(Eigen::Map<const RowMatrix>(w.data(), points_, components_));
}

Eigen::VectorXd ExactRoundTrip::round_trip(const Eigen::VectorXd& y, const RowMatrix& base) const {
  const RowMatrix inner = to_inner(y);
  RowMatrix at_output = RowMatrix::Zero(static_cast<Eigen::Index>(rows_.size()), inner.cols());
  for (std::size_t k = 0; k < rows_.size(); ++k)
    if (!held_[k]) at_output.row(static_cast<Eigen::Index>(k)) = inner.row(rows_[k]);
  if (base.size() > 0) at_output += base;
  return flatten(output_->map(at_output));
}

Eigen::MatrixXd ExactRoundTrip::round_trip_matrix() const {
  const Eigen::Index n = points_ * components_;
  Eigen::MatrixXd matrix(n, n);
  Eigen::VectorXd unit = Eigen::VectorXd::Zero(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    unit(j) = 1.0;
    const Eigen::VectorXd column = round_trip(unit, RowMatrix());
    if (column.size() != n)
      throw std::invalid_argument(
          "ExactRoundTrip: the output mapper does not map back onto the points the input "
          "mapper maps from");
    matrix.col(j) = column;
    unit(j) = 0.0;
  }
  return matrix;
}

RowMatrix ExactRoundTrip::map(const RowMatrix& w, const RowMatrix& base) {
  if (input_ == nullptr) throw std::logic_error("ExactRoundTrip::map called before build");
  if (w.rows() != points_ || w.cols() != components_ ||
      (base.size() > 0 &&
       (base.rows() != static_cast<Eigen::Index>(rows_.size()) || base.cols() != components_)))
    throw std::invalid_argument("ExactRoundTrip::map: w or base has the wrong shape");
  if (!factorised_) factorise();
  const Eigen::VectorXd target = flatten(w);
  if (reached_rows_.empty()) return to_inner(target);  // no driven node reaches a point
  const Eigen::VectorXd missed = target - round_trip(target, base);
  plain_defect_ = largest(missed, reached_rows_);
  // y = w + d, d the least-squares solution of M d = w - (M w + L base) of least norm.
  Eigen::VectorXd y = target;
  y(reached_columns_) += solver_.solve(Eigen::VectorXd(missed(reached_rows_)));
  const Eigen::VectorXd left = target - round_trip(y, base);
  defect_ = largest(left, reached_rows_);
  return to_inner(y);
}

}  // namespace cocopp
