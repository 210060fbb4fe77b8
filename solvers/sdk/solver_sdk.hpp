#pragma once
// cocopp solver SDK: link this into a solver executable to be driven by the cocopp coupler.
//
//   class MySolver : public cocopp::sdk::Solver { ... };
//   int main(int argc, char** argv) { MySolver s; return cocopp::sdk::serve(s, argc, argv); }
//
// serve() connects to the coupler (the channel is given in the environment, see
// docs/protocol.md), answers its requests until told to stop and returns the exit code.
// Exceptions thrown by the Solver's methods are sent to the coupler as error messages.
// The SDK has no dependency beyond the C++ standard library.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/protocol/interface_description.hpp"

namespace cocopp::sdk {

/// Thrown by Solver::solve() when the solver cannot solve the time step for this input (a mesh
/// the input would turn inside out, a structure loaded beyond what it can carry) but still
/// holds the step's start state: the coupler is told (REJECTED), the solver serves on, and the
/// coupler may call solve() again with another input. Any other exception ends the solver.
class InputRejected : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Interface data layout (both directions): for each model part in order, for each of its
/// (input or output) variables in order, all points, components contiguous.
class Solver {
 public:
  virtual ~Solver() = default;
  virtual InterfaceDescription initialize(const RunInfo& run) = 0;
  virtual void initialize_step(std::int32_t step, double time) = 0;
  /// One coupling iteration: solve from the state of the last committed step.
  virtual std::vector<double> solve(const std::vector<double>& input) = 0;
  virtual void finalize_step() = 0;
  virtual void output_step() {}
  virtual void finalize() {}

  /// Restart support. A solver that can restart returns true; save_restart(step) then writes
  /// what it needs to continue after `step` (the step it finalized last; the coupler asks
  /// whenever it saves its own state), and initialize() with run.timestep_start > 0 reads
  /// that back instead of starting from its initial state. A solver that returns false is
  /// never asked to save, and a restart of it stops with an error that says so.
  virtual bool can_restart() const { return false; }
  virtual void save_restart(std::int32_t /*step*/) {}

  /// Solver-coupling convergence (the coupler's `solver_coupling_convergence` criterion). The
  /// coupler calls start_reporting_convergence() once, before the first step, when the case
  /// asks; from then on it reads converged_at_first_iteration() after every solve(): whether
  /// the solver's own iterations (Newton, an outer loop) converged at their first iteration,
  /// i.e. the new input changed the solution by less than the solver's own tolerance. For that
  /// a solver may start each coupling iteration from the previous iterate instead of the
  /// step's start. A solver that cannot tell keeps the default, which throws: the coupler
  /// stops with that message.
  virtual void start_reporting_convergence() {
    throw std::runtime_error(
        "this solver cannot report whether its own iterations converged at their first "
        "iteration (solver-coupling convergence)");
  }
  virtual bool converged_at_first_iteration() const { return false; }

  /// Substeps (docs/protocol.md, SUBSTEPS): the case may let a solver take k steps of its own
  /// per coupling time step (a window). The SDK then drives the window: the solver sees a run
  /// of time step delta_t / k whose steps are the substeps (initialize() gets both divided and
  /// multiplied accordingly, save_restart() the substep), and every coupling iteration is k of
  /// its steps from the window's start: initialize_step(), solve() with the input at that
  /// substep's end, finalize_substep() but for the last (the coupler finalizes that one once
  /// the window has converged). For that a solver keeps its committed state in memory:
  /// save_state() (at the window's start) and restore_state() (before the next iteration of
  /// the window). A solver that can returns true here.
  virtual bool can_substep() const { return false; }
  /// The end of a substep inside a window that has not converged yet: the next substep starts
  /// from it. By default finalize_step(); a solver that writes its results there may leave
  /// that to the window's end.
  virtual void finalize_substep() { finalize_step(); }
  virtual void save_state() {}
  virtual void restore_state() {}
};

/// Whether the command line asks for help (--help or -h): solvers print their usage then.
bool wants_help(int argc, char** argv);

/// Serve the coupler's requests until it says stop. Returns 0 on a normal stop, 1 on errors.
int serve(Solver& solver, int argc, char** argv);

}  // namespace cocopp::sdk
