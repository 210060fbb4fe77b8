#include "coupler/coupled_solvers/models/secant_columns.hpp"

#include <algorithm>

#include "core/case/settings.hpp"
#include "coupler/coupled_solvers/models/linear_combination.hpp"

namespace cocopp {

ColumnFilter ColumnFilter::read(const Settings& s) {
  ColumnFilter f;
  f.min_significant = s.get_in_range("min_significant", f.min_significant, Range::non_negative());
  f.min_significant_relative = s.get_in_range("min_significant_relative",
                                              f.min_significant_relative, Range::closed(0.0, 1.0));
  const std::string order = s.get_choice("filter_order", "newest", {"newest", "smallest"});
  f.order = order == "smallest" ? Order::kSmallest : Order::kNewest;
  return f;
}

void SecantColumns::insert(Eigen::VectorXd v, Eigen::VectorXd w) {
  const double norm = v.norm();
  if (norm == 0.0) {
    notes_.push_back("a repeated residual (zero residual difference) gave no secant column");
    return;
  }
  columns_.push_front({std::move(v), std::move(w), 0, next_id_++});
  norms_.push_front(norm);
  if (!qr_.insert_front(columns_.front().v)) refactorize();
  filter();
}

void SecantColumns::restore(Column column) {
  column.id = next_id_++;
  const double norm = column.v.norm();
  columns_.push_back(std::move(column));
  norms_.push_back(norm);
  if (!qr_.append(columns_.back().v)) refactorize();
}

bool SecantColumns::significant(Eigen::Index i) const {
  const double r_ii = qr_.diagonal(i);
  return r_ii > 0.0 && r_ii >= filter_.min_significant &&
         r_ii >= filter_.min_significant_relative * norms_[std::size_t(i)];
}

Eigen::Index SecantColumns::next_to_drop() const {
  Eigen::Index chosen = -1;
  double smallest = 0.0;
  for (Eigen::Index i = 0; i < qr_.columns(); ++i) {
    if (significant(i)) continue;
    // Newest first: removing a column changes only the R_ii of the older ones.
    if (filter_.order == ColumnFilter::Order::kNewest) return i;
    // Smallest first, scaled as the criterion that fails (the relative one in its own norm).
    const double size = filter_.min_significant_relative > 0.0
                            ? qr_.diagonal(i) / norms_[std::size_t(i)]
                            : qr_.diagonal(i);
    if (chosen < 0 || size < smallest) {
      chosen = i;
      smallest = size;
    }
  }
  return chosen;
}

void SecantColumns::drop(Eigen::Index i) {
  qr_.remove(i);
  columns_.erase(columns_.begin() + i);
  norms_.erase(norms_.begin() + i);
}

void SecantColumns::filter() {
  for (Eigen::Index i = next_to_drop(); i >= 0; i = next_to_drop()) drop(i);
}

void SecantColumns::refactorize() {
  // Used when an update would be inaccurate (a new column numerically in the span of the
  // others). A column numerically dependent on newer ones is dropped here; filter() then
  // applies the thresholds.
  qr_.clear();
  for (std::size_t i = 0; i < columns_.size();) {
    if (qr_.append(columns_[i].v)) {
      ++i;
      continue;
    }
    columns_.erase(columns_.begin() + std::ptrdiff_t(i));
    norms_.erase(norms_.begin() + std::ptrdiff_t(i));
    notes_.push_back(
        "a secant column numerically dependent on newer ones (more columns than unknowns, or a "
        "repeated direction) was dropped");
  }
}

void SecantColumns::rescale(const Eigen::VectorXd& factors) {
  for (std::size_t i = 0; i < columns_.size(); ++i) {
    columns_[i].v = columns_[i].v.cwiseProduct(factors);
    norms_[i] = columns_[i].v.norm();
  }
  refactorize();
  filter();
}

void SecantColumns::age_and_drop(int max_age) {
  for (auto& column : columns_) ++column.age;
  while (!columns_.empty() && columns_.back().age > max_age) {
    columns_.pop_back();
    norms_.pop_back();
    qr_.remove_last();
  }
}

template <class Member>
Eigen::VectorXd SecantColumns::combine(const Eigen::VectorXd& c, Member member) const {
  // W may be longer than V (secondary data in the output only).
  const Eigen::Index n = columns_.empty() ? 0 : (columns_.front().*member).size();
  Eigen::VectorXd result = Eigen::VectorXd::Zero(n);
  add_linear_combination(result, c, [&](Eigen::Index j) -> const Eigen::VectorXd& {
    return columns_[std::size_t(j)].*member;
  });
  return result;
}

Eigen::VectorXd SecantColumns::combine_w(const Eigen::VectorXd& c) const {
  return combine(c, &Column::w);
}

Eigen::VectorXd SecantColumns::combine_v(const Eigen::VectorXd& c) const {
  return combine(c, &Column::v);
}

void SecantColumns::save_state(State& state) const {
  if (empty()) {
    state.set("v", Eigen::MatrixXd());
    state.set("w", Eigen::MatrixXd());
    state.set("age", Eigen::VectorXd());
    return;
  }
  state.set("v", v_matrix());
  state.set("w", w_matrix());
  Eigen::VectorXd ages(size());
  for (int i = 0; i < size(); ++i) ages(i) = columns_[std::size_t(i)].age;
  state.set("age", ages);
  qr_.save_state(state.group("qr"));
}

void SecantColumns::load_state(const State& state) {
  const Eigen::MatrixXd& v = state.matrix("v");
  const Eigen::MatrixXd& w = state.matrix("w");
  const Eigen::VectorXd ages = state.vector("age");
  columns_.clear();
  norms_.clear();
  qr_.clear();
  for (Eigen::Index i = 0; i < ages.size(); ++i)  // saved newest first: append keeps the order
    restore({v.col(i), w.col(i), int(ages(i))});
  // The saved factors, not the rebuilt ones, which differ in round-off (state files written
  // before they were saved have none: the rebuilt ones stay).
  if (state.has_group("qr")) qr_.load_state(state.group("qr"), v.rows(), ages.size());
}

namespace {

template <class Member>
Eigen::MatrixXd as_matrix(const std::deque<SecantColumns::Column>& columns, Member member) {
  Eigen::MatrixXd m((columns.front().*member).size(), Eigen::Index(columns.size()));
  for (std::size_t i = 0; i < columns.size(); ++i) m.col(Eigen::Index(i)) = columns[i].*member;
  return m;
}

}  // namespace

Eigen::MatrixXd SecantColumns::v_matrix() const {
  return as_matrix(columns_, &Column::v);
}
Eigen::MatrixXd SecantColumns::w_matrix() const {
  return as_matrix(columns_, &Column::w);
}

}  // namespace cocopp
