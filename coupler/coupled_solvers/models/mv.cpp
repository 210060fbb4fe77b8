// `mv`: J_prev as a dense matrix.
#include "coupler/coupled_solvers/models/multi_vector.hpp"

namespace cocopp {
namespace {

class MultiVectorDense : public MultiVector {
 public:
  explicit MultiVectorDense(const Settings& s) : MultiVector(s) {}

 protected:
  Eigen::VectorXd apply_previous(const Eigen::VectorXd& y) const override {
    if (jacobian_.size() == 0) return Eigen::VectorXd::Zero(y.size());
    return jacobian_ * y;
  }

  void keep(StepColumns step) override {
    const Eigen::Index n = step.rows();
    if (jacobian_.size() == 0) jacobian_ = Eigen::MatrixXd::Zero(n, n);
    // J += (W - J V) V^+ with V^+ = R^-1 Q^T from the step's QR factorization, the one
    // predict() used (then mv and mvmf differ by round-off only), written with V R^-1 = Q as
    // J += (W R^-1 - J Q) Q^T: two n x n x k products. (Forming V^+ column by column from unit
    // vectors, as before, cost n solves and allocations: 190 µs per iteration on the tube.)
    const QrFactorization& qr = step.qr();
    const Eigen::MatrixXd q = qr.basis() * qr.u();
    Eigen::MatrixXd mismatch = step.w_matrix();
    qr.r().triangularView<Eigen::Upper>().solveInPlace<Eigen::OnTheRight>(mismatch);
    mismatch.noalias() -= jacobian_ * q;
    jacobian_.noalias() += mismatch * q.transpose();
    columns_kept_ += step.size();
  }

  int previous_columns() const override { return columns_kept_; }

  void rescale_previous(const Eigen::VectorXd& factors) override {
    // J_prev maps weighted residual differences: D r in the new weights is r in the old.
    if (jacobian_.size() > 0) jacobian_ = jacobian_ * factors.cwiseInverse().asDiagonal();
  }

  void save_previous(State& state) const override {
    state.set("jacobian", jacobian_);
    state.set("columns_kept", double(columns_kept_));
  }
  void load_previous(const State& state) override {
    jacobian_ = state.matrix("jacobian");
    columns_kept_ = int(state.scalar("columns_kept"));
  }

 private:
  Eigen::MatrixXd jacobian_;  ///< J_prev; empty until a step has added columns
  int columns_kept_ = 0;      ///< all columns of previous steps: J_prev never forgets
};

}  // namespace

COCOPP_REGISTER(ModelRegistry, "mv", MultiVectorDense)

}  // namespace cocopp
