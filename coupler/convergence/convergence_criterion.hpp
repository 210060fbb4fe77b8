#pragma once
// Convergence criteria decide when the coupling iterations of a time step stop.
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "core/case/registry.hpp"

namespace cocopp {

class SolverWrapper;

/// A tolerance a criterion compares the residual with: of the residual's `order`-norm ("1",
/// "2", "inf"), relative to the step's first iteration or absolute. For plots of the residual
/// history against it (the results file keeps them).
struct Tolerance {
  bool relative = false;
  std::string order = "2";
  double value = 0.0;
};

class ConvergenceCriterion {
 public:
  static constexpr const char* kind = "convergence criterion";
  virtual ~ConvergenceCriterion() = default;

  /// Called once, after both solvers started: criteria that ask a solver (solver-coupling
  /// convergence) take it here; `solvers` in the case's order.
  virtual void attach_solvers(const std::array<SolverWrapper*, 2>& /*solvers*/) {}
  /// Called at the start of every time step.
  virtual void initialize_step() = 0;
  /// Called with the residual r = x~ - x of every coupling iteration.
  virtual void update(const Eigen::VectorXd& residual) = 0;
  /// Called before update() with the solver output the residual belongs to (x~; y~ for the
  /// loads' criterion side by side): for criteria relative to the values.
  virtual void set_output(const Eigen::VectorXd& /*output*/) {}
  /// Stop iterating.
  virtual bool is_satisfied() const = 0;
  /// Stopped because the tolerance was met (not only because of an iteration limit).
  virtual bool tolerance_met() const { return is_satisfied(); }
  /// An iteration limit in it is reached (the step ends whatever else is measured).
  virtual bool limit_reached() const { return false; }
  /// Where the last residual stands as this criterion measures it, for the progress line
  /// (e.g. "relative 3.1e-07"); "" when the 2-norm the line shows already says it.
  virtual std::string progress() const { return ""; }
  /// One line for the run header, e.g. "relative_norm(2) < 1e-06".
  virtual std::string describe() const = 0;
  /// The tolerances it compares the residual with (none for an iteration limit).
  virtual std::vector<Tolerance> tolerances() const { return {}; }
};

using ConvergenceCriterionRegistry = Registry<ConvergenceCriterion>;

}  // namespace cocopp
