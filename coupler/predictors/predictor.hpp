#pragma once
// Predictors give the interface displacement x at the start of a time step from the converged
// values of previous steps.
#include <Eigen/Core>
#include <deque>

#include "core/case/registry.hpp"

namespace cocopp {

class Predictor {
 public:
  static constexpr const char* kind = "predictor";
  virtual ~Predictor() = default;

  /// Start from the initial interface values.
  virtual void initialize(const Eigen::VectorXd& x0) = 0;
  /// The prediction for the coming step.
  virtual Eigen::VectorXd predict() const = 0;
  /// Record the converged value of the step that just ended.
  virtual void update(const Eigen::VectorXd& x) = 0;
  /// Converged values, newest first (the state to save for a restart).
  virtual const std::deque<Eigen::VectorXd>& history() const = 0;
  /// Continue from a saved history (newest first).
  virtual void restore(std::deque<Eigen::VectorXd> history) = 0;
};

using PredictorRegistry = Registry<Predictor>;

}  // namespace cocopp
