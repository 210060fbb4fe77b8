#pragma once
// SecantColumns: the column pairs (v, w) = (residual difference, solver output difference) a
// least-squares secant model fits, newest first, with the QR factorization of V and the
// filtering both the `ls` and the multi-vector models use.
//
// Filtering: a column whose |R_ii| (the part not explained by the newer columns) is below
// `min_significant` (absolute, CoCoNuT's criterion) or below `min_significant_relative` times
// its own norm (preCICE's QR3) carries no new information: it is removed for good, so older,
// nearly dependent columns make way for newer ones. `filter_order` says which insignificant
// column goes first: `newest` (the default: the first one scanning from the newest, whose
// removal changes only the older ones' R_ii) or `smallest` (the one with the smallest R_ii, as
// CoCoNuT does; then the QR is updated and the scan repeated).
#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <string>
#include <utility>
#include <vector>

#include "coupler/coupled_solvers/models/qr_factorization.hpp"
#include "coupler/results/state.hpp"

namespace cocopp {

class Settings;

struct ColumnFilter {
  enum class Order { kNewest, kSmallest };
  double min_significant = 1e-12;
  double min_significant_relative = 0.0;
  Order order = Order::kNewest;
  /// Reads `min_significant`, `min_significant_relative` and `filter_order` from a model's
  /// settings.
  static ColumnFilter read(const Settings& settings);
};

class SecantColumns {
 public:
  struct Column {
    Eigen::VectorXd v;     ///< residual difference
    Eigen::VectorXd w;     ///< solver output difference
    int age = 0;           ///< time steps since the column was made (0: current step)
    std::uint64_t id = 0;  ///< unique within these columns (set by insert and restore)
  };

  explicit SecantColumns(ColumnFilter filter = {}) : filter_(filter) {}

  int size() const { return static_cast<int>(columns_.size()); }
  bool empty() const { return columns_.empty(); }
  Eigen::Index rows() const { return columns_.empty() ? 0 : columns_.front().v.size(); }
  const std::deque<Column>& columns() const { return columns_; }

  /// Add a column pair in front (age 0), then drop the insignificant columns. A zero or
  /// repeated residual, or more columns than rows, ends up dropped here, never as NaN.
  void insert(Eigen::VectorXd v, Eigen::VectorXd w);
  /// Add a column at the back (oldest) as it was saved, without filtering: for restoring.
  void restore(Column column);

  /// Degenerate columns dropped since the last call, as readable notes (for warnings).
  std::vector<std::string> take_notes() { return std::exchange(notes_, {}); }

  /// The QR factorization of V (for products of two models: CrossProjection).
  const QrFactorization& qr() const { return qr_; }

  /// c = V^+ y = argmin ||V c - y||.
  Eigen::VectorXd coefficients(const Eigen::VectorXd& y) const { return qr_.solve(y); }
  /// W c and V c.
  Eigen::VectorXd combine_w(const Eigen::VectorXd& c) const;
  Eigen::VectorXd combine_v(const Eigen::VectorXd& c) const;

  /// The residual's weights changed (scaling: residual_sum): every v times `factors` (new
  /// weight over old, per value), the QR factorization recomputed and the filter applied.
  void rescale(const Eigen::VectorXd& factors);
  /// A time step ended: every column gets one step older; those older than `max_age` go.
  void age_and_drop(int max_age);

  /// V, W and the ages as arrays `v`, `w`, `age`; load_state() replaces the columns.
  void save_state(State& state) const;
  void load_state(const State& state);

  Eigen::MatrixXd v_matrix() const;
  Eigen::MatrixXd w_matrix() const;

 private:
  bool significant(Eigen::Index i) const;
  /// The insignificant column to drop next under the filter's order, or -1 if there is none.
  Eigen::Index next_to_drop() const;
  void drop(Eigen::Index i);
  void filter();
  void refactorize();
  template <class Member>
  Eigen::VectorXd combine(const Eigen::VectorXd& c, Member member) const;

  ColumnFilter filter_;
  std::deque<Column> columns_;  ///< newest first, matching the columns of qr_
  std::deque<double> norms_;    ///< ||v|| of each column
  QrFactorization qr_;
  std::uint64_t next_id_ = 1;
  std::vector<std::string> notes_;
};

}  // namespace cocopp
