// `ls`: the least-squares model of IQN-ILS (Degroote et al.).
//
// V = [dr^i] and W = [dx~^i] hold differences between consecutive coupling iterations of the
// current time step and of the q previous ones, newest first (SecantColumns, which also
// filters them). predict(dr) solves c = argmin ||V c - dr|| with the QR factorization of V and
// returns W c. The factorization is updated as columns come and go rather than recomputed,
// which keeps an iteration O(n k).
#include "coupler/coupled_solvers/models/model.hpp"
#include "coupler/coupled_solvers/models/secant_columns.hpp"

namespace cocopp {
namespace {

class LeastSquares : public Model {
 public:
  explicit LeastSquares(const Settings& s)
      : reused_steps_(s.get_int_in_range("q", 0, 0)), columns_(ColumnFilter::read(s)) {}

  void initialize_step() override { has_reference_ = false; }

  void add(const Eigen::VectorXd& r, const Eigen::VectorXd& xt) override {
    if (has_reference_) columns_.insert(r - r_ref_, xt - xt_ref_);
    r_ref_ = r;
    xt_ref_ = xt;
    has_reference_ = true;
  }

  bool is_ready() const override { return !columns_.empty(); }

  void rescale(const Eigen::VectorXd& factors) override {
    columns_.rescale(factors);
    if (has_reference_) r_ref_ = r_ref_.cwiseProduct(factors);
  }

  Eigen::VectorXd predict(const Eigen::VectorXd& dr) override {
    if (columns_.empty()) return Eigen::VectorXd::Zero(xt_ref_.size());
    return columns_.combine_w(columns_.coefficients(dr));
  }

  bool fits_residuals() const override { return true; }

  Eigen::VectorXd fitted(const Eigen::VectorXd& dr) override {
    if (columns_.empty()) return Eigen::VectorXd::Zero(dr.size());
    return columns_.combine_v(columns_.coefficients(dr));
  }

  const SecantColumns* least_squares_columns() const override { return &columns_; }

  void finalize_step() override { columns_.age_and_drop(reused_steps_); }

  int columns() const override { return columns_.size(); }

  void save_state(State& state) const override { columns_.save_state(state); }
  std::vector<std::string> take_notes() override { return columns_.take_notes(); }
  void load_state(const State& state) override { columns_.load_state(state); }

 private:
  int reused_steps_;
  SecantColumns columns_;
  Eigen::VectorXd r_ref_, xt_ref_;
  bool has_reference_ = false;
};

}  // namespace

COCOPP_REGISTER(ModelRegistry, "ls", LeastSquares)

}  // namespace cocopp
