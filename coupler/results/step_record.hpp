#pragma once
// What a run's outputs (coupler/outputs: the HDF5 results, the summary, ParaView, ...) are told
// about it: a description known at the start, one record per finished time step and, for those
// that ask, one per coupling iteration. Plain data, so the coupled solvers fill them without
// depending on any file format.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "coupler/convergence/convergence_criterion.hpp"

namespace cocopp {

/// What is known at the start of a run.
struct RunDescription {
  std::string case_file;                  ///< path as given on the command line
  std::string coupled_solver;             ///< type, e.g. "iqni"
  std::vector<std::string> solver_names;  ///< the two solver wrappers, in order
  double delta_t = 0;                     ///< s
  int timestep_start = 0;
  int number_of_timesteps = 0;
  bool restarted = false;             ///< continues a saved state (timestep_start is its step)
  std::string convergence_criterion;  ///< ConvergenceCriterion::describe()
  std::vector<Tolerance> tolerances;  ///< what the criterion compares the residual with
};

/// One converged (or accepted) time step.
struct StepRecord {
  int step = 0;
  double time = 0;                     ///< s, at the end of the step
  int iterations = 0;                  ///< coupling iterations
  std::vector<double> residual_norms;  ///< 2-norm of the residual, one per iteration
  double wall_time = 0;                ///< s, whole step
  std::vector<double> solver_times;    ///< s, per solver wrapper, same order as solver_names
  double coupler_time = 0;             ///< s, wall_time minus the solver times
  bool converged = true;  ///< false: accepted at an iteration limit without meeting the tolerance
  /// Not converged, but the last residual at the solvers' noise (CoupledSolver::noise_floor):
  /// a criterion that cannot be met there, not a coupling that does not converge.
  bool at_noise = false;
  /// The last residual as the convergence criterion measures it ("relative 3.1e-07"), for the
  /// progress line; not written to the results.
  std::string criterion_progress;
  int surrogate_iterations = 0;  ///< iqnism: the coupling iterations of its surrogate
  /// Degenerate situations the coupled solver handled and went on (a repeated residual, more
  /// secant columns than unknowns), each once with a count: "... (3 times)".
  std::vector<std::string> warnings;
  /// The step's solution: x (displacement) and y (loads) in the layouts the outputs were
  /// opened with, and the watchpoints' values there (empty without watchpoints).
  Eigen::VectorXd x, y, watchpoints;
};

/// One coupling iteration as it ends, for `cocopp run --verbose` and the outputs that write
/// iterations.
struct IterationReport {
  int step;
  int iteration;
  double residual;        ///< 2-norm of r = x~ - x
  std::string criterion;  ///< the residual as the criterion measures it (may be empty)
  double step_seconds;    ///< wall time since the step started
  /// The iteration's input x, the loads y it gave and its residual r, in x's and y's layouts;
  /// valid during the call only.
  const Eigen::VectorXd* x = nullptr;
  const Eigen::VectorXd* y = nullptr;
  const Eigen::VectorXd* residual_vector = nullptr;
};

}  // namespace cocopp
