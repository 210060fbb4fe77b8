#pragma once
// Polynomial extrapolation, the base of the predictors constant, linear, legacy, quadratic and
// cubic (one file each).
// Each is a weighted sum of the newest converged values; with too little history they fall
// back to the highest order the history allows.
#include <deque>
#include <utility>
#include <vector>

#include "coupler/predictors/predictor.hpp"

namespace cocopp {

class Extrapolation : public Predictor {
 public:
  using Weights = std::vector<double>;  ///< weight of x^n, x^(n-1), ...

  Extrapolation(const Settings&, Weights weights) : weights_(std::move(weights)) {}

  void initialize(const Eigen::VectorXd& x0) override { history_ = {x0}; }

  Eigen::VectorXd predict() const override {
    const Weights& w = weights_.size() <= history_.size() ? weights_ : fallback();
    Eigen::VectorXd x = Eigen::VectorXd::Zero(history_.front().size());
    for (std::size_t i = 0; i < w.size(); ++i) x += w[i] * history_[i];
    return x;
  }

  void update(const Eigen::VectorXd& x) override {
    history_.push_front(x);
    if (history_.size() > weights_.size()) history_.pop_back();
  }

  const std::deque<Eigen::VectorXd>& history() const override { return history_; }
  void restore(std::deque<Eigen::VectorXd> history) override { history_ = std::move(history); }

 private:
  /// The extrapolation of the highest order the current history supports.
  const Weights& fallback() const {
    static const std::vector<Weights> by_points = {
        {1.0}, {2.0, -1.0}, {3.0, -3.0, 1.0}, {4.0, -6.0, 4.0, -1.0}};
    return by_points[history_.size() - 1];
  }

  Weights weights_;
  std::deque<Eigen::VectorXd> history_;
};

}  // namespace cocopp
