// `ls`: the least-squares model of IQN-ILS (Degroote et al.).
//
// V = [dr^i] and W = [dx~^i] hold differences between consecutive coupling iterations of the
// current time step and of the q previous ones, newest first. predict(dr) solves
// c = argmin ||V c - dr|| with the QR factorization of V and returns W c.
//
// Filtering: a column whose |R_ii| (the part not explained by the newer columns) is below
// `min_significant` (absolute, CoCoNuT's criterion) or below `min_significant_relative` times
// its own norm (preCICE's QR3) carries no new information: it is removed for good, so older,
// nearly dependent columns make way for newer ones. The factorization is updated as columns
// come and go rather than recomputed, which keeps an iteration O(n k).
#include <deque>

#include "coupler/coupled_solvers/models/model.hpp"
#include "coupler/coupled_solvers/models/qr_factorization.hpp"

namespace cocopp {
namespace {

class LeastSquares : public Model {
 public:
  explicit LeastSquares(const Settings& s)
      : reused_steps_(s.get_int_in_range("q", 0, 0)),
        min_significant_(s.get_in_range("min_significant", 1e-12, Range::non_negative())),
        min_significant_relative_(
            s.get_in_range("min_significant_relative", 0.0, Range::closed(0.0, 1.0))) {}

  void initialize_step() override { has_reference_ = false; }

  void add(const Eigen::VectorXd& r, const Eigen::VectorXd& xt) override {
    if (has_reference_) insert(r - r_ref_, xt - xt_ref_);
    r_ref_ = r;
    xt_ref_ = xt;
    has_reference_ = true;
  }

  bool is_ready() const override { return !columns_.empty(); }

  Eigen::VectorXd predict(const Eigen::VectorXd& dr) override {
    if (columns_.empty()) return Eigen::VectorXd::Zero(xt_ref_.size());
    const Eigen::VectorXd c = qr_.solve(dr);
    Eigen::VectorXd dxt = Eigen::VectorXd::Zero(columns_.front().w.size());
    for (std::size_t i = 0; i < columns_.size(); ++i) dxt += c(Eigen::Index(i)) * columns_[i].w;
    return dxt;
  }

  void finalize_step() override {
    for (auto& column : columns_) ++column.age;
    while (!columns_.empty() && columns_.back().age > reused_steps_) {
      columns_.pop_back();
      qr_.remove_last();
    }
  }

  int columns() const override { return static_cast<int>(columns_.size()); }

 private:
  struct Column {
    Eigen::VectorXd v;  ///< residual difference
    Eigen::VectorXd w;  ///< solver output difference
    double norm;        ///< ||v||
    int age;            ///< time steps since the column was made (0: current step)
  };

  void insert(Eigen::VectorXd v, Eigen::VectorXd w) {
    const double norm = v.norm();
    columns_.push_front({std::move(v), std::move(w), norm, 0});
    if (!qr_.insert_front(columns_.front().v)) refactorize();
    filter();
  }

  bool significant(Eigen::Index i) const {
    const double r_ii = qr_.diagonal(i);
    return r_ii > 0.0 && r_ii >= min_significant_ &&
           r_ii >= min_significant_relative_ * columns_[std::size_t(i)].norm;
  }

  /// Remove insignificant columns, newest first; removing one changes only the later ones.
  void filter() {
    for (Eigen::Index i = 0; i < qr_.columns();) {
      if (significant(i)) {
        ++i;
        continue;
      }
      qr_.remove(i);
      columns_.erase(columns_.begin() + i);
    }
  }

  /// Factorize anew, newest column first; used when an update would be inaccurate (a new
  /// column numerically in the span of the others). A column numerically dependent on newer
  /// ones is dropped here; filter() then applies the thresholds.
  void refactorize() {
    qr_.clear();
    for (auto it = columns_.begin(); it != columns_.end();)
      it = qr_.append(it->v) ? std::next(it) : columns_.erase(it);
  }

  int reused_steps_;
  double min_significant_;
  double min_significant_relative_;
  std::deque<Column> columns_;  ///< newest first, matching the columns of qr_
  QrFactorization qr_;
  Eigen::VectorXd r_ref_, xt_ref_;
  bool has_reference_ = false;
};

}  // namespace

COCOPP_REGISTER(ModelRegistry, "ls", LeastSquares)

}  // namespace cocopp
