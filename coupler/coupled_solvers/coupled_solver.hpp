#pragma once
// CoupledSolver: runs the coupling iterations of one time step between two solver wrappers.
//
// Notation (as in CoCoNuT): the first solver F maps the interface displacement x to loads y,
// the second S maps y back to a displacement x~; the residual is r = x~ - x. The solvers are
// run by a CouplingScheme chosen with `scheme` (coupler/schemes: serial, F then S, iterates on
// x; parallel, F and S side by side, on x and y stacked), which also starts, times and steps
// back; the base class owns the iteration loop, the predictor, the convergence criterion and
// the divergence checks; each coupled solver only says how the next unknown follows from the
// unknown u, its image u~ and r = u~ - u (`next_input`: x, x~ and r in the serial scheme) and
// what it keeps between steps (its state).
#include <Eigen/Core>
#include <array>
#include <chrono>
#include <functional>
#include <memory>
#include <string>

#include "coupler/convergence/convergence_criterion.hpp"
#include "coupler/predictors/predictor.hpp"
#include "coupler/results/run_outcome.hpp"
#include "coupler/results/state.hpp"
#include "coupler/results/step_record.hpp"
#include "coupler/schemes/coupling_scheme.hpp"
#include "coupler/schemes/stopwatch.hpp"
#include "solver_wrappers/solver_wrapper.hpp"

namespace cocopp {

class Model;

class CoupledSolver {
 public:
  static constexpr const char* kind = "coupled solver";
  explicit CoupledSolver(const Settings& settings);
  virtual ~CoupledSolver();

  /// Start both solvers (the `scheme` of them) and check that their interfaces fit together.
  void initialize(SolverWrapper& first, SolverWrapper& second);
  /// Create what the coupled solver itself runs besides the case's two solvers (iqnism's
  /// surrogate solvers), from its settings; called once, while the case is read.
  virtual void create_own_solvers(const RunSettings& /*run*/) {}
  /// Stop what create_own_solvers() started; called once, at the end of a run.
  virtual void finalize() {}
  /// Between steps, before the state is saved: both solvers (and the coupled solver's own)
  /// keep what a run restarted after `step` needs (SolverWrapper::save_restart).
  void save_solver_restarts(int step);
  /// Called after every coupling iteration (a CFD step can take minutes: a user wants to see
  /// it move).
  void set_iteration_observer(std::function<void(const IterationReport&)> observer) {
    iteration_observer_ = std::move(observer);
  }
  /// The step being computed when a run stopped in it (0 if none) and the residual norms of
  /// its iterations so far.
  int unfinished_step() const { return unfinished_step_; }
  const std::vector<double>& unfinished_residuals() const { return unfinished_residuals_; }
  /// Advance, iterate to convergence, commit and write one time step.
  StepRecord solve_step(int step, double time);
  /// The two halves of solve_step(), for a coupled solver run inside another (a surrogate):
  /// iterate one step to convergence, then commit it. Between them, synchronize(x) makes x the
  /// step's solution: one more pass of both solvers at x, so that they commit x's state.
  StepRecord iterate_step(int step, double time);
  void synchronize(const Eigen::VectorXd& x);
  void commit_step(StepRecord& record);
  /// The secant model of the coupled problem's inverse Jacobian, dx~ for a residual change dr,
  /// in the interface's own units (iqni without scaling); nullptr where there is none.
  virtual Model* residual_model() { return nullptr; }
  /// The interfaces x (displacement) and y (loads): during a step the values of the current
  /// coupling iteration (y as given to the second solver), after it the converged values of
  /// the step.
  const Interface& x() const;
  const Interface& y() const;
  /// The interfaces the iterated unknown is made of ({x} serial, {x, y} parallel): what the
  /// vectors given to next_input() are laid out as.
  std::vector<const Interface*> unknown_layouts() const;
  /// Whether the solvers run side by side (`scheme: parallel`): known from construction on.
  bool side_by_side() const { return scheme_type_ == "parallel"; }
  /// "iqni (omega 0.05, model ls q 10), predictor linear, until (...)": for the run header.
  std::string describe() const;
  /// When a step's iterations stop.
  const ConvergenceCriterion& criterion() const { return *criterion_; }
  /// The memory a restarted run needs to continue as this one would (predictor history and
  /// the type's own: secant columns, Aitken's factor, scaling weights), between time steps.
  void save_state(State& state) const;
  /// Continue from a saved state (after initialize()); throws std::runtime_error if it does
  /// not fit this coupled solver or interface. With `own` false only the predictor's history
  /// is taken: the type's own memory (secant columns, Aitken's factor, scaling) starts afresh,
  /// so that another coupled solver can continue the run.
  void load_state(const State& state, bool own = true);
  /// Wall time spent in each solver since initialize(), in seconds.
  /// Case errors of this coupled solver with these solvers, found when the case is loaded: a
  /// solver that takes substeps needs a type and a scheme that iterate on windows.
  void check_solvers(const SolverWrapper& first, const SolverWrapper& second) const;
  const std::array<double, 2>& solver_time_total() const {
    static const std::array<double, 2> none{};
    return scheme_ ? scheme_->total_times() : none;  // (no scheme: initialize() failed)
  }
  /// Wall time during which a solver ran since initialize(): the sum of solver_time_total()
  /// less what they ran side by side.
  double solvers_wall_time_total() const {
    return scheme_ ? scheme_->total_solvers_wall_time() : 0.0;
  }
  /// Wall time spent in the coupled solver's own solvers (iqnism's surrogate, its coupling
  /// included) since initialize(), in seconds: not the coupler's time.
  double own_solvers_time_total() const { return own_solvers_time_total_; }

 protected:
  /// The next x of the iteration, given the current x, the output x~ of the second solver and
  /// the residual r = x~ - x.
  virtual Eigen::VectorXd next_input(const Eigen::VectorXd& x, const Eigen::VectorXd& xt,
                                     const Eigen::VectorXd& r) = 0;
  /// The loads given to the second solver, from this iteration's x and the first solver's
  /// output y~ = F(x): y~ itself, except in methods that also update y (ibqn).
  virtual Eigen::VectorXd second_solver_input(const Eigen::VectorXd& /*x*/,
                                              const Eigen::VectorXd& yt) {
    return yt;
  }
  /// What the convergence criterion measures of an iteration whose residual is r = x~ - x:
  /// r itself, except in methods whose second solver gets loads other than F(x) (ibqn).
  virtual Eigen::VectorXd convergence_residual(const Eigen::VectorXd& r) { return r; }
  /// The iteration that met the convergence criterion (no next_input follows): its secant
  /// information is still worth keeping for the next steps.
  virtual void on_converged(const Eigen::VectorXd& /*x*/, const Eigen::VectorXd& /*xt*/,
                            const Eigen::VectorXd& /*r*/) {}
  /// Hooks for methods with memory across iterations and steps; on_initialized() runs once
  /// the interfaces x() and y() are known.
  virtual void on_initialized() {}
  virtual void on_step_start() {}
  virtual void on_step_end() {}
  /// Explicit coupling makes one pass per step.
  virtual bool iterates() const { return true; }
  /// Degenerate situations handled since the last call, for the step's warnings.
  virtual std::vector<std::string> take_notes() { return {}; }
  /// save_solver_restarts() for the coupled solver's own solvers.
  virtual void save_own_solver_restarts(int /*step*/) {}
  /// The type's own part of the state.
  virtual void save_own_state(State&) const {}
  virtual void load_own_state(const State&) {}
  /// The step's first x, from the predictor's: the predictor's (iqnism may use its surrogate).
  virtual Eigen::VectorXd first_input(const Eigen::VectorXd& predicted) { return predicted; }
  /// The type's own settings for describe(), e.g. "omega 0.05".
  virtual std::string describe_settings() const { return ""; }
  /// What to suggest when this method diverges: by default, to a method without a model
  /// (relaxation, Gauss-Seidel), a quasi-Newton method.
  virtual std::string divergence_advice() const;
  /// The advice for a quasi-Newton method with first relaxation `omega`: it already is one.
  static std::string quasi_newton_advice(double omega);

  /// Whether this type can iterate on a window of substeps (its unknown x over the window):
  /// not one that updates S's loads itself (ibqn) or models x = S(F(x)) with a surrogate of
  /// its own (iqnism).
  virtual bool takes_substeps() const { return true; }
  /// For a type whose iteration is serial by construction: `scheme: parallel` is a case error
  /// that says `why`.
  void require_serial_scheme(const Settings& settings, const std::string& why) const {
    if (side_by_side())
      settings.fail("scheme", "coupled solver '" + type_ +
                                  "' cannot run the solvers side by side: " + why +
                                  " (use iqni, aitken or relaxation with scheme: parallel)");
  }

  /// The scope of a Stopwatch counts as time of the coupled solver's own solvers (its
  /// surrogate, say), not the coupler's.
  struct OwnSolversStopwatch;
  /// Iterations of the coupled solver's own coupling (iqnism's surrogate) in this step, for
  /// the step's record.
  void set_own_iterations(int iterations) { own_iterations_ = iterations; }
  /// The step being solved (iterate_step's arguments).
  int current_step() const { return step_; }
  double current_time() const { return time_; }

  std::string type_;

 private:
  /// Throws DivergenceError; a growth at the solvers' noise level becomes a note instead.
  void check_divergence(const std::vector<double>& norms, int step, double time,
                        std::vector<std::string>& notes) const;

  /// The saved predictor history laid out as this scheme's unknown (another scheme's, for a
  /// fresh coupled solver: `own` false); throws when it cannot be.
  Eigen::MatrixXd predictor_history(const Eigen::MatrixXd& saved, bool own) const;
  /// Whether the iterations stop after one with residual r and output u~ (laid out as the
  /// unknown).
  bool update_criteria(const Eigen::VectorXd& r, const Eigen::VectorXd& ut, bool& tolerance_met);
  /// The criteria's progress text for the step's line (side by side: and the loads' residual).
  std::string progress() const;

  std::string scheme_type_;
  Settings scheme_settings_;  ///< the coupled solver's: for the scheme's errors
  std::string predictor_type_;
  std::unique_ptr<Predictor> predictor_;
  std::unique_ptr<ConvergenceCriterion> criterion_;
  /// Parallel schemes: the criterion of the load residual y~ - y (`load_criterion`), if set.
  std::unique_ptr<ConvergenceCriterion> load_criterion_;
  double last_load_residual_ = 0.0;  ///< ||y~ - y|| of the last iteration (side by side)
  double divergence_factor_;
  int growth_iterations_;                       ///< 0: off
  Waveform::Interpolation time_interpolation_;  ///< `time_interpolation` (substeps)
  bool time_average_;                           ///< `time_average` (substeps)
  CouplingScheme::Backtracking backtracking_;
  std::unique_ptr<CouplingScheme> scheme_;  ///< the case's two solvers, after initialize()
  std::chrono::steady_clock::time_point step_start_;
  std::function<void(const IterationReport&)> iteration_observer_;
  int unfinished_step_ = 0;
  std::vector<double> unfinished_residuals_;
  int step_ = 0;
  double time_ = 0.0;
  double own_solvers_time_step_ = 0.0, own_solvers_time_total_ = 0.0;
  int own_iterations_ = 0;
  /// The largest residual of a step's first iteration in the run: the scale the noise floor of
  /// the growth check is measured against.
  double largest_first_residual_ = 0.0;
  static constexpr double kNoiseFloor = 1e-6;
  /// A displacement residual below this fraction of the interface's size per value is
  /// round-off, whatever the run's residuals were (a run that starts at rest has none larger).
  static constexpr double kRoundOff = 1e-12;
  /// The residual below which a step's iterations are the solvers' noise: kNoiseFloor of the
  /// run's largest first residual, or round-off of the interface's size (kRoundOff).
  double noise_floor() const;
};

struct CoupledSolver::OwnSolversStopwatch {
  explicit OwnSolversStopwatch(CoupledSolver& owner)
      : stopwatch(owner.own_solvers_time_step_, owner.own_solvers_time_total_) {}
  Stopwatch stopwatch;
};

using CoupledSolverRegistry = Registry<CoupledSolver>;

}  // namespace cocopp
