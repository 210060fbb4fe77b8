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
    // V^+ column by column from the step's QR factorization, the one predict() used: then
    // mv and mvmf differ by round-off only.
    Eigen::MatrixXd pseudo_inverse(step.size(), n);
    for (Eigen::Index j = 0; j < n; ++j)
      pseudo_inverse.col(j) = step.coefficients(Eigen::VectorXd::Unit(n, j));
    const Eigen::MatrixXd mismatch = step.w_matrix() - jacobian_ * step.v_matrix();
    jacobian_.noalias() += mismatch * pseudo_inverse;
    columns_kept_ += step.size();
  }

  int previous_columns() const override { return columns_kept_; }

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
