#pragma once
// SolverWrapper: what the coupler sees of a solver. Every wrapper (a solver process and the
// built-in tube types, a mapped wrapper, openfoam, calculix) implements this, so the coupling
// algorithms never know which solver is behind an interface; only the coupling scheme
// (coupler/schemes) asks one whether it adopts the other's interface (a mapped wrapper).
#include <Eigen/Core>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "core/case/registry.hpp"
#include "core/case/run_settings.hpp"
#include "core/data/interface.hpp"
#include "solver_wrappers/solver_error.hpp"

namespace cocopp {

class SolverWrapper {
 public:
  static constexpr const char* kind = "solver wrapper";
  virtual ~SolverWrapper() = default;

  /// The name used in messages and results (`name` in the case, default: the type).
  virtual const std::string& name() const = 0;
  /// The name an enclosing wrapper (`mapped`) passes on when the case names only the enclosing
  /// one: then this wrapper's log, restart files and messages carry the name the user gave.
  /// A name given in the case wins.
  virtual void set_default_name(const std::string& /*name*/) {}
  /// One line for the run header: what runs where (command, working directory, log file).
  virtual std::string describe() const { return name(); }
  /// After initialize(): what was started, for the run header, e.g. "flow (pid 1234)".
  virtual std::string started() const { return name(); }
  /// Validate what can be validated without running (input files exist, executable found).
  virtual void check() const {}
  /// What `cocopp check` adds to check(): read the solver's own input file as the solver will
  /// (the built-in tube solvers), so that a typo there is found before a run. A run leaves it
  /// to the solver, which reports the same error when it starts.
  virtual void check_solver_input() const {}
  /// The solver's own input file (YAML), if the wrapper knows it: empty otherwise. Tools that
  /// change a solver's parameters (cocopp bench's solver_inputs) edit this file.
  virtual std::filesystem::path input_file() const { return {}; }

  /// Begin starting the solver without waiting for it (launch its process), so that the
  /// coupler can start both solvers side by side; initialize() finishes the start. Wrappers
  /// with nothing to launch ahead leave it empty: initialize() alone does everything.
  virtual void start() {}
  /// Start the solver (if start() did not) and learn its interfaces (layout and initial values).
  virtual void initialize() = 0;
  virtual const Interface& input_interface() const = 0;
  virtual const Interface& output_interface() const = 0;

  /// Wrappers that present the other solver's interface (a mapped wrapper) return true and
  /// adopt it here, after both solvers are initialized: `input` is what the other solver gives,
  /// `output` what it takes. Others keep their own interfaces.
  virtual bool adopts_interfaces() const { return false; }
  virtual void adopt_interfaces(const Interface& /*input*/, const Interface& /*output*/) {}
  /// After adopt_interfaces(): for each point of the adopted output model part `part`, how far
  /// it lies from what this solver covers (0 inside its mesh; infinite where it gives nothing).
  /// A `group` gives each point to the member that covers it. Wrappers that do not adopt
  /// interfaces cover everything they give.
  virtual Eigen::VectorXd output_distances(const std::string& part) const {
    for (const auto& block : output_interface().blocks())
      if (block.model_part == part) return Eigen::VectorXd::Zero(block.points);
    return {};
  }

  /// From now on initialize_step(), finalize_step() and output_step() may return as soon as
  /// the request is on its way; the solver's answer (or its error, named after that request
  /// and step) is taken by complete_step_requests() or by the next request that waits for an
  /// answer (solve(), save_restart(), finalize()). The coupler asks for this, so that both
  /// solvers work on these requests side by side instead of one round trip after the other; a
  /// caller that reads the solver's files after finalize_step() does not ask. Wrappers may
  /// ignore it.
  virtual void overlap_step_requests() {}
  /// Wait for the answers to the requests sent so far (see overlap_step_requests()).
  virtual void complete_step_requests() {}
  /// Advance to time step `step` (time = step * delta_t).
  virtual void initialize_step(int step, double time) = 0;
  /// One coupling iteration: solve the step with `input`, return the output interface.
  virtual const Interface& solve(const Interface& input) = 0;
  /// Steps the solver takes per coupling time step (its `substeps`): the coupling iterates on
  /// whole windows of them (docs/coupling.md, "Substeps"). 1 for most solvers.
  virtual int substeps() const { return 1; }
  /// One coupling iteration of a window: `inputs` holds the input at the end of each of the
  /// substeps(), one column each, laid out as input_interface(); returns the output at each,
  /// one column each (output_interface() then holds the last). With one substep, solve().
  virtual Eigen::MatrixXd solve_substeps(const Eigen::MatrixXd& inputs) {
    if (inputs.cols() != substeps())
      throw std::logic_error(name() + ": solve_substeps() was given " +
                             std::to_string(inputs.cols()) + " substeps' inputs, expected " +
                             std::to_string(substeps()));
    Interface input = input_interface();
    input.set_data(inputs.col(0));
    return solve(input).data();
  }
  /// Solver-coupling convergence (the `solver_coupling_convergence` criterion): from now on,
  /// every solve() also finds out whether the solver's own iterations (Newton, PIMPLE's outer
  /// loop) converged at their first iteration, i.e. whether the input changed its solution by
  /// less than the solver's own tolerance. Called once, after initialize(), only when the
  /// case's criterion asks. Throws SolverError saying why when the solver cannot tell.
  virtual void start_reporting_convergence() {
    throw SolverError(name(), "solver '" + name() +
                                  "' cannot report whether its own iterations converged at "
                                  "their first iteration, which the "
                                  "solver_coupling_convergence criterion needs");
  }
  /// After solve(): that answer for the last solve (false before reporting started).
  virtual bool converged_at_first_iteration() const { return false; }
  /// Commit the converged state of the step.
  virtual void finalize_step() = 0;
  /// Write the solver's own output for the step.
  virtual void output_step() = 0;
  /// Keep what the solver needs to restart after `step`, the step finalized last (the coupler
  /// asks whenever it saves its own state). A restarted run gives the wrapper
  /// RunSettings::timestep_start = that step; a wrapper that cannot restart refuses
  /// timestep_start > 0 with a message that says so (in its constructor or initialize()).
  virtual void save_restart(int /*step*/) {}
  /// Stop the solver. Safe to call more than once, and after a failure.
  virtual void finalize() = 0;
};

using SolverWrapperRegistry = Registry<SolverWrapper, const RunSettings&>;

}  // namespace cocopp
