#pragma once
// SerialScheme: the two solvers of a coupled problem run one after the other (the serial
// scheme of CoCoNuT and preCICE): the first, F, maps the interface displacement x to loads y;
// the second, S, maps y back to a displacement x~. It does everything a time step asks of the
// solvers, so that a coupled solver (coupler/coupled_solvers) sees only x, x~ and r = x~ - x:
// it starts them side by side and fits their interfaces together (a mapped wrapper adopts the
// other's), advances, commits and writes them with a step's requests overlapped, times each,
// checks what they return for NaN, and steps back from an input a solver rejects.
#include <Eigen/Core>
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "core/data/interface.hpp"
#include "solver_wrappers/solver_wrapper.hpp"

namespace cocopp {

class SerialScheme {
 public:
  /// coupled_solver.backtracking: how often, and by how much, x steps back towards the last
  /// input both solvers accepted when one rejects it (retries 0: a rejection stops the run).
  struct Backtracking {
    int retries = 4;
    double factor = 0.5;
  };
  /// The loads S takes for this iteration's x and F's output y~: y~ itself unless set
  /// (ibqn updates y too).
  using LoadsUpdate =
      std::function<Eigen::VectorXd(const Eigen::VectorXd& x, const Eigen::VectorXd& yt)>;

  /// `divergence_advice`: what to suggest when a solver returns NaN (the coupled solver's).
  SerialScheme(SolverWrapper& first, SolverWrapper& second, Backtracking backtracking,
               std::string divergence_advice);

  /// Start both solvers side by side, learn and fit their interfaces. x() starts at the
  /// displacement S reports for its initial state.
  void start();
  /// x (displacement, F's input layout) and y (loads, F's output layout): during a step the
  /// values of the current coupling iteration (y as given to S), after it the step's solution.
  const Interface& x() const { return x_; }
  const Interface& y() const { return y_; }
  /// The step's solution (or a restart's starting point): what x() holds between steps.
  void set_x(const Eigen::VectorXd& x) { x_.set_data(x); }
  std::array<SolverWrapper*, 2> solvers() const { return solvers_; }
  void set_loads_update(LoadsUpdate update) { loads_update_ = std::move(update); }

  /// Advance both solvers to `step` (time = step * delta_t); the step's solver times start at 0.
  void begin_step(int step, double time);
  /// One coupling iteration: y = F(x), x~ = S(y); returns x~. Throws DivergenceError naming the
  /// solver, model part and point of a non-finite value.
  Eigen::VectorXd evaluate(const Eigen::VectorXd& x, int iteration);
  /// evaluate(), but when a solver rejects x (SolverRejectedInput) x steps back towards
  /// `accepted`, the last input both solvers solved, as Backtracking says; each step back is
  /// noted in `notes`. Throws SolverError once the retries are used up.
  Eigen::VectorXd evaluate_stepping_back(Eigen::VectorXd& x, const Eigen::VectorXd& accepted,
                                         int iteration, std::vector<std::string>& notes);
  /// Both solvers commit the step and write their output, side by side.
  void commit_step();
  /// Both solvers keep what a run restarted after `step` needs.
  void save_restarts(int step);

  /// Wall time in each solver during the current (or last) step, and since start(), in s.
  const std::array<double, 2>& step_times() const { return step_times_; }
  const std::array<double, 2>& total_times() const { return total_times_; }

 private:
  template <class Call>
  void timed(int index, Call call);
  const Interface& timed_solve(int index, const Interface& input);
  void check_finite(const Interface& data, const SolverWrapper& solver, int iteration) const;
  void adopt_interfaces();
  void check_interfaces_match() const;

  std::array<SolverWrapper*, 2> solvers_;
  Backtracking backtracking_;
  std::string divergence_advice_;
  LoadsUpdate loads_update_;
  Interface x_, y_;  ///< layouts of F's input and output
  int step_ = 0;
  std::array<double, 2> step_times_{};
  std::array<double, 2> total_times_{};
};

}  // namespace cocopp
