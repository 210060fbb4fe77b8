#pragma once
// The base of `mv` (IQN-MVJ) and `mvmf` (mv.cpp, mvmf.cpp): the multi-vector models (Lindner et al.
// 2015; CoCoNuT's mv and mvmf), which carry an approximation of the inverse Jacobian from time step
// to time step.
//
// Within a step, V and W hold the differences of r and x~ between consecutive iterations
// (newest first, filtered as in `ls`), and the estimate is
//   J = J_prev + (W - J_prev V) V^+,   V^+ = (V^T V)^-1 V^T = R^-1 Q^T,
// the smallest change of J_prev (in the Frobenius norm) with J V = W. So
//   predict(dr) = J dr = W c + J_prev (dr - V c),   c = V^+ dr,
// and when the step ends J_prev <- J. J_prev starts at 0: the first step is IQN-ILS.
//
// `mv` stores J_prev as a dense n x n matrix (O(n^2) per prediction and memory). `mvmf` never
// forms it: it applies the recursion above to the V, W and QR factorization kept from each of
// the last q steps (J_prev of the oldest kept step is 0), O(n k) per kept step.
#include <deque>

#include "coupler/coupled_solvers/models/model.hpp"
#include "coupler/coupled_solvers/models/secant_columns.hpp"

namespace cocopp {

/// The secant columns of one time step (newest first, filtered as in `ls`) and one level of
/// the recursion.
class StepColumns : public SecantColumns {
 public:
  using SecantColumns::SecantColumns;

  /// Returns W c for c = V^+ y and leaves y - V c, the part of y this step's columns do not
  /// explain, in y (for the previous steps' Jacobian).
  Eigen::VectorXd peel(Eigen::VectorXd& y) const {
    if (empty()) return Eigen::VectorXd::Zero(y.size());
    if (q_.cols() == size()) {  // frozen: V c = Q p and W c = W R^-1 p, with p = Q^T y
      const Eigen::VectorXd p = q_.transpose() * y;
      y.noalias() -= q_ * p;
      return w_r_inverse_ * p;
    }
    const Eigen::VectorXd c = coefficients(y);
    y -= combine_v(c);
    return combine_w(c);
  }

  /// For a step that takes no more columns (mvmf's kept steps, each peeled in every
  /// prediction): Q and W R^-1 as two dense n x k matrices, so that peel() is three
  /// contiguous products instead of the factorization's solve and two sums over columns.
  void freeze() {
    if (empty()) return;
    q_ = qr().basis() * qr().u();
    w_r_inverse_ = w_matrix();
    qr().r().triangularView<Eigen::Upper>().solveInPlace<Eigen::OnTheRight>(w_r_inverse_);
  }

 private:
  Eigen::MatrixXd q_;            ///< Q, once frozen
  Eigen::MatrixXd w_r_inverse_;  ///< W R^-1, once frozen
};

/// The part shared by `mv` and `mvmf`: the current step's columns and the prediction; the
/// two differ only in how they store J_prev.
class MultiVector : public Model {
 public:
  explicit MultiVector(const Settings& s) : filter_(ColumnFilter::read(s)), current_(filter_) {}

  void initialize_step() override {
    has_reference_ = false;
    current_ = StepColumns(filter_);
  }

  void add(const Eigen::VectorXd& r, const Eigen::VectorXd& xt) override {
    if (has_reference_) current_.insert(r - r_ref_, xt - xt_ref_);
    r_ref_ = r;
    xt_ref_ = xt;
    has_reference_ = true;
  }

  /// The carried Jacobian is secant information too: the first iteration of a step already
  /// uses it instead of relaxing.
  bool is_ready() const override { return columns() > 0; }

  Eigen::VectorXd predict(const Eigen::VectorXd& dr) override {
    Eigen::VectorXd rest = dr;
    const Eigen::VectorXd dxt = current_.peel(rest);
    return dxt + apply_previous(rest);
  }

  void finalize_step() override {
    // A step that converged in its first iteration has no columns: J_prev stays as it is.
    if (!current_.empty()) keep(std::move(current_));
    current_ = StepColumns(filter_);
  }

  /// New weights of the residuals (side by side, scaling residual_sum): the current step's
  /// columns re-expressed, and J_prev (mv: exactly, J_prev D^-1; mvmf: each kept step's
  /// columns re-expressed and its QR redone, as preCICE does, which changes its min-norm
  /// update a little).
  void rescale(const Eigen::VectorXd& factors) override {
    current_.rescale(factors);
    if (has_reference_) r_ref_ = r_ref_.cwiseProduct(factors);
    rescale_previous(factors);
  }

  /// The current step's columns plus those of previous steps still held in J_prev.
  int columns() const override { return current_.size() + previous_columns(); }

  std::vector<std::string> take_notes() override { return current_.take_notes(); }

  /// At a step boundary the current step has no columns: J_prev is the whole state.
  void save_state(State& state) const override { save_previous(state); }
  void load_state(const State& state) override {
    current_ = StepColumns(filter_);
    load_previous(state);
  }

 protected:
  const ColumnFilter& filter() const { return filter_; }
  virtual void save_previous(State& state) const = 0;
  virtual void load_previous(const State& state) = 0;
  /// J_prev y.
  virtual Eigen::VectorXd apply_previous(const Eigen::VectorXd& y) const = 0;
  /// J_prev <- J_prev + (W - J_prev V) V^+ for a finished step's (non-empty) columns.
  virtual void keep(StepColumns step) = 0;
  virtual int previous_columns() const = 0;
  virtual void rescale_previous(const Eigen::VectorXd& factors) = 0;

 private:
  ColumnFilter filter_;
  StepColumns current_;
  Eigen::VectorXd r_ref_, xt_ref_;
  bool has_reference_ = false;
};

}  // namespace cocopp
