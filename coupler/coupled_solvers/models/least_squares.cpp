// `ls`: the least-squares model of IQN-ILS (Degroote et al.).
//
// V = [dr^i] and W = [dx~^i] hold differences between consecutive coupling iterations of the
// current time step and of the q previous ones, newest first. predict(dr) solves
// c = argmin ||V c - dr|| with a QR decomposition of V and returns W c.
//
// Filtering: V is orthogonalised column by column, newest first (classical Gram-Schmidt with
// one re-orthogonalisation, which is as stable as Householder here and cheap to update). A
// column whose remaining norm |R_ii| is below `min_significant` (absolute, CoCoNuT's criterion)
// or below `min_significant_relative` times its own norm (preCICE's QR3) carries no new
// information: it is removed for good, so older, nearly dependent columns make way for newer.
#include <deque>

#include "coupler/coupled_solvers/models/model.hpp"

namespace cocopp {
namespace {

class LeastSquares : public Model {
 public:
  explicit LeastSquares(const Settings& s)
      : reused_steps_(s.get_int_in_range("q", 0, 0)),
        min_significant_(s.get_in_range("min_significant", 1e-12, Range::non_negative())),
        min_significant_relative_(s.get_in_range("min_significant_relative", 0.0, Range::closed(0.0, 1.0))) {}

  void initialize_step() override { has_reference_ = false; }

  void add(const Eigen::VectorXd& r, const Eigen::VectorXd& xt) override {
    if (has_reference_) columns_.push_front({r - r_ref_, xt - xt_ref_, 0});
    r_ref_ = r;
    xt_ref_ = xt;
    has_reference_ = true;
    factorized_ = false;
  }

  bool is_ready() const override { return !columns_.empty(); }

  Eigen::VectorXd predict(const Eigen::VectorXd& dr) override {
    if (!factorized_) factorize();
    if (columns_.empty()) return Eigen::VectorXd::Zero(xt_ref_.size());
    const Eigen::VectorXd c =
        r_.triangularView<Eigen::Upper>().solve(q_.transpose() * dr);
    Eigen::VectorXd dxt = Eigen::VectorXd::Zero(columns_.front().w.size());
    for (std::size_t i = 0; i < columns_.size(); ++i) dxt += c(Eigen::Index(i)) * columns_[i].w;
    return dxt;
  }

  void finalize_step() override {
    for (auto& column : columns_) ++column.age;
    while (!columns_.empty() && columns_.back().age > reused_steps_) columns_.pop_back();
    factorized_ = false;
  }

  int columns() const override { return static_cast<int>(columns_.size()); }

 private:
  struct Column {
    Eigen::VectorXd v;  ///< residual difference
    Eigen::VectorXd w;  ///< solver output difference
    int age;            ///< time steps since the column was made (0: current step)
  };

  /// Orthogonalise the columns newest first, dropping the insignificant ones.
  void factorize() {
    const Eigen::Index n = r_ref_.size();
    const auto k = static_cast<Eigen::Index>(columns_.size());
    q_.resize(n, k);
    r_ = Eigen::MatrixXd::Zero(k, k);
    Eigen::Index kept = 0;
    for (auto it = columns_.begin(); it != columns_.end();) {
      const auto Q = q_.leftCols(kept);
      Eigen::VectorXd v = it->v;
      Eigen::VectorXd h = Q.transpose() * v;
      v -= Q * h;
      const Eigen::VectorXd h2 = Q.transpose() * v;  // re-orthogonalise once
      v -= Q * h2;
      const double r_ii = v.norm();
      if (r_ii < min_significant_ || r_ii < min_significant_relative_ * it->v.norm() ||
          r_ii == 0.0) {
        it = columns_.erase(it);
        continue;
      }
      r_.col(kept).head(kept) = h + h2;
      r_(kept, kept) = r_ii;
      q_.col(kept) = v / r_ii;
      ++kept;
      ++it;
    }
    q_.conservativeResize(n, kept);
    r_.conservativeResize(kept, kept);
    factorized_ = true;
  }

  int reused_steps_;
  double min_significant_;
  double min_significant_relative_;
  std::deque<Column> columns_;  ///< newest first
  Eigen::VectorXd r_ref_, xt_ref_;
  bool has_reference_ = false;
  bool factorized_ = false;
  Eigen::MatrixXd q_, r_;
};

}  // namespace

COCOPP_REGISTER(ModelRegistry, "ls", LeastSquares)

}  // namespace cocopp
