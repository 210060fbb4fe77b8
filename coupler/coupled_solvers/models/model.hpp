#pragma once
// Secant models: approximate the (inverse) Jacobian of the coupled problem from the residual
// and output differences of past coupling iterations. Used by the quasi-Newton coupled solvers.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/case/registry.hpp"
#include "coupler/results/state.hpp"

namespace cocopp {

class SecantColumns;

class Model {
 public:
  static constexpr const char* kind = "model";
  virtual ~Model() = default;

  /// Called at the start of every time step.
  virtual void initialize_step() = 0;
  /// Record one coupling iteration's residual r and solver output x~ (differences with the
  /// previous iteration of the same step become the secant information).
  virtual void add(const Eigen::VectorXd& r, const Eigen::VectorXd& xt) = 0;
  /// Whether the model holds any secant information.
  virtual bool is_ready() const = 0;
  /// Approximate dx~ for a residual change dr (from the least-squares fit W c, V c ~ dr).
  virtual Eigen::VectorXd predict(const Eigen::VectorXd& dr) = 0;
  /// Whether the model is such a least-squares fit, so that fitted() is defined.
  virtual bool fits_residuals() const { return false; }
  /// The part of dr the secant columns reproduce: V c of predict()'s fit.
  virtual Eigen::VectorXd fitted(const Eigen::VectorXd& dr) {
    return Eigen::VectorXd::Zero(dr.size());
  }
  /// The secant columns of a model whose predict() is W c with c = argmin ||V c - dr|| (`ls`),
  /// so that a product of two such models can be formed in the small space of their columns
  /// (ibqn); nullptr for any other model.
  virtual const SecantColumns* least_squares_columns() const { return nullptr; }
  /// The weights of the residuals it was given changed by `factors` (new over old, per
  /// value): express what it holds in the new ones (scaling residual_sum).
  virtual void rescale(const Eigen::VectorXd& factors) = 0;
  /// Called when the time step converged: keep this step's information for reuse.
  virtual void finalize_step() = 0;
  /// Number of secant columns currently in use (for reports and tests).
  virtual int columns() const = 0;
  /// What the model carries from step to step, at a step boundary (after finalize_step), and
  /// back: a model loaded from a saved state predicts exactly as the one that saved it.
  virtual void save_state(State& state) const = 0;
  /// Degenerate situations handled since the last call (dropped zero or dependent columns).
  virtual std::vector<std::string> take_notes() { return {}; }
  virtual void load_state(const State& state) = 0;
};

using ModelRegistry = Registry<Model>;

}  // namespace cocopp
