#pragma once
// CouplingScheme: how the two solvers of a coupled problem are run in one coupling iteration,
// chosen by name with the coupled solver's `scheme` key (docs/coupling.md, "Schemes"):
//   serial    F then S: x~ = S(F(x)), the unknown is x (CoCoNuT's and preCICE's serial scheme)
//   parallel  F and S side by side on the same iterate: (x~, y~) = (S(y), F(x)), the unknown
//             is x and y stacked (preCICE's parallel-implicit scheme)
// The base does everything else a time step asks of the solvers, so that a coupled solver
// (coupler/coupled_solvers) sees only the unknown u, its image u~ and r = u~ - u: it starts
// both solvers side by side and fits their interfaces together (a mapped wrapper adopts the
// other's), advances, commits and writes them with a step's requests overlapped, times each,
// checks what they return for NaN, and steps back from an input a solver rejects.
#include <Eigen/Core>
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "core/case/registry.hpp"
#include "core/data/interface.hpp"
#include "coupler/schemes/stopwatch.hpp"
#include "coupler/schemes/waveform.hpp"
#include "solver_wrappers/solver_wrapper.hpp"

namespace cocopp {

class CouplingScheme {
 public:
  static constexpr const char* kind = "coupling scheme";
  /// coupled_solver.backtracking: how often, and by how much, the unknown steps back towards
  /// the last input both solvers accepted when one rejects it (retries 0: a rejection stops
  /// the run).
  struct Backtracking {
    int retries = 4;
    double factor = 0.5;
  };
  /// What a scheme runs: the case's two solvers, F (displacement -> loads) first.
  struct Parts {
    SolverWrapper* first = nullptr;
    SolverWrapper* second = nullptr;
    Backtracking backtracking;
    std::string divergence_advice;  ///< what to suggest when a solver returns NaN
    /// How a solver that takes substeps gets the other's values between its samples.
    Waveform::Interpolation interpolation = Waveform::Interpolation::kLinear;
    /// A structure with fewer substeps than the flow takes the mean of the loads over each of
    /// its steps (their impulse), or else their values at its steps' ends.
    bool time_average = true;
  };
  /// The loads S takes for this iteration's x and F's output y~: y~ itself unless set
  /// (ibqn updates y too; serial schemes only).
  using LoadsUpdate =
      std::function<Eigen::VectorXd(const Eigen::VectorXd& x, const Eigen::VectorXd& yt)>;

  explicit CouplingScheme(Parts parts);
  virtual ~CouplingScheme() = default;

  /// Start both solvers side by side, learn and fit their interfaces. x() starts at the
  /// displacement S reports for its initial state, y() at the loads F reports for its own.
  void start();
  /// x (displacement, F's input layout) and y (loads, F's output layout): during a step the
  /// values of the current coupling iteration (y as given to S), after it the step's solution.
  const Interface& x() const { return x_; }
  const Interface& y() const { return y_; }
  std::array<SolverWrapper*, 2> solvers() const { return solvers_; }

  /// The interfaces the unknown is made of, one after the other ({x}, or {x, y}).
  virtual std::vector<const Interface*> unknown_layouts() const = 0;
  /// The unknown as the solvers last took it (between steps: the step's solution), and set.
  virtual Eigen::VectorXd unknown() const = 0;
  virtual void set_unknown(const Eigen::VectorXd& u) = 0;
  /// The displacement residual x~ - x within a residual laid out as the unknown: what the
  /// convergence criterion measures in every scheme.
  Eigen::VectorXd displacement_part(const Eigen::VectorXd& r) const {
    return r.head(displacement_size());
  }
  /// The load residual y~ - y within it (empty where y is not part of the unknown).
  Eigen::VectorXd loads_part(const Eigen::VectorXd& r) const {
    return r.tail(r.size() - displacement_size());
  }
  void set_loads_update(LoadsUpdate update) { loads_update_ = std::move(update); }

  /// Advance both solvers to `step` (time = step * delta_t); the step's solver times start at 0.
  void begin_step(int step, double time);
  /// One coupling iteration: u~ = G(u). Throws DivergenceError naming the solver, model part
  /// and point of a non-finite value.
  virtual Eigen::VectorXd evaluate(const Eigen::VectorXd& u, int iteration) = 0;
  /// evaluate(), but when a solver rejects its input (SolverRejectedInput) u steps back towards
  /// `accepted`, the last unknown both solvers solved, as Backtracking says; each step back is
  /// noted in `notes`. Throws SolverError once the retries are used up.
  Eigen::VectorXd evaluate_stepping_back(Eigen::VectorXd& u, const Eigen::VectorXd& accepted,
                                         int iteration, std::vector<std::string>& notes);
  /// Both solvers commit the step and write their output, side by side.
  void commit_step();
  /// Both solvers keep what a run restarted after `step` needs.
  void save_restarts(int step);

  /// Wall time in each solver during the current (or last) step, and since start(), in s.
  const std::array<double, 2>& step_times() const { return step_times_; }
  const std::array<double, 2>& total_times() const { return total_times_; }
  /// Wall time during which a solver ran in the current step: the sum of step_times() less
  /// what the solvers ran side by side.
  double step_solvers_wall_time() const { return step_times_[0] + step_times_[1] - step_overlap_; }
  /// The same since start().
  double total_solvers_wall_time() const {
    return total_times_[0] + total_times_[1] - total_overlap_;
  }

 protected:
  /// How many values of the unknown are displacement (x; all its substeps' with substeps).
  virtual Eigen::Index displacement_size() const { return x_.size(); }
  /// After start(): the interfaces are known (x_ and y_ hold the initial values).
  virtual void on_started() {}
  /// In begin_step(), after the solvers were told.
  virtual void on_step_begun() {}
  template <class Call>
  void timed(int index, Call call);
  const Interface& timed_solve(int index, const Interface& input);
  void check_finite(const Interface& data, const SolverWrapper& solver, int iteration) const;
  /// A section of `seconds` in which both solvers ran side by side (parallel schemes).
  void add_overlap(double seconds) {
    step_overlap_ += seconds;
    total_overlap_ += seconds;
  }

  std::array<SolverWrapper*, 2> solvers_;
  LoadsUpdate loads_update_;
  Interface x_, y_;  ///< layouts of F's input and output
  int step_ = 0;
  Waveform::Interpolation interpolation_;
  bool time_average_;

 private:
  void adopt_interfaces();
  void check_interfaces_match() const;

  Backtracking backtracking_;
  std::string divergence_advice_;
  std::array<double, 2> step_times_{};
  std::array<double, 2> total_times_{};
  double step_overlap_ = 0.0;
  double total_overlap_ = 0.0;
};

template <class Call>
void CouplingScheme::timed(int index, Call call) {
  // Also a call that throws (a rejected input) took the solver's time, not the coupler's.
  const Stopwatch stopwatch(step_times_[index], total_times_[index]);
  call();
}

/// Schemes are created by name (coupled_solver.scheme) from the coupled solver's settings.
using CouplingSchemeRegistry = Registry<CouplingScheme, CouplingScheme::Parts>;

}  // namespace cocopp
