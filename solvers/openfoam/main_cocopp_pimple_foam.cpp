// cocoppPimpleFoam: pimpleFoam with a moving mesh, driven by the cocopp coupler. It stays
// running for the whole simulation; see pimple_foam_solver.hpp for what one step and one
// coupling iteration do, and docs/solver-wrappers-openfoam.md for the case set-up.
//
//   cocoppPimpleFoam -patches '(wall)'                     (started by `cocopp run`)
//   mpirun -np 2 cocoppPimpleFoam -parallel -patches '(wall)'
//
// In parallel the master rank talks to the coupler and passes every request on to the other
// ranks (all of OpenFOAM's work is collective); it gathers the loads.
#include <cstdint>
#include <iostream>

#include "solvers/openfoam/pimple_foam_solver.hpp"

namespace {

using cocopp::openfoam::PimpleFoamSolver;
namespace sdk = cocopp::sdk;

enum class Command : Foam::label {
  kInitialize = 1,
  kInitializeStep,
  kSolve,
  kFinalizeStep,
  kOutputStep,
  kFinalize,
  kExit,  ///< the coupler stopped before initializing
  kSaveRestart,
  kReportConvergence,
  kSaveState,  ///< substeps: a window's start
  kRestoreState,
  kFinalizeSubstep
};

/// From the master to every other rank: a command and its numbers. Nothing in a serial run.
void broadcast(Command command, const std::vector<double>& numbers = {}) {
  Foam::label code = static_cast<Foam::label>(command);
  Foam::Pstream::scatter(code);
  Foam::scalarList values(static_cast<Foam::label>(numbers.size()));
  std::copy(numbers.begin(), numbers.end(), values.begin());
  Foam::Pstream::scatter(values);
}

/// The master's solver: each request goes to the other ranks first, then every rank runs it.
class MasterSolver : public sdk::Solver {
 public:
  explicit MasterSolver(PimpleFoamSolver& solver) : solver_(solver) {}

  sdk::InterfaceDescription initialize(const sdk::RunInfo& run) override {
    broadcast(Command::kInitialize, {run.delta_t, static_cast<double>(run.timestep_start)});
    started_ = true;
    return solver_.initialize(run);
  }
  void initialize_step(std::int32_t step, double time) override {
    broadcast(Command::kInitializeStep, {static_cast<double>(step), time});
    solver_.initialize_step(step, time);
  }
  std::vector<double> solve(const std::vector<double>& input) override {
    broadcast(Command::kSolve, input);
    return solver_.solve(input);
  }
  void finalize_step() override {
    broadcast(Command::kFinalizeStep);
    solver_.finalize_step();
  }
  void output_step() override {
    broadcast(Command::kOutputStep);
    solver_.output_step();
  }
  bool can_substep() const override { return solver_.can_substep(); }
  void save_state() override {
    broadcast(Command::kSaveState);
    solver_.save_state();
  }
  void restore_state() override {
    broadcast(Command::kRestoreState);
    solver_.restore_state();
  }
  void finalize_substep() override {
    broadcast(Command::kFinalizeSubstep);
    solver_.finalize_substep();
  }
  bool can_restart() const override { return solver_.can_restart(); }
  void save_restart(std::int32_t step) override {
    broadcast(Command::kSaveRestart, {static_cast<double>(step)});
    solver_.save_restart(step);
  }
  /// The master checks first (no collective work): a refusal then reaches the coupler while
  /// the other ranks still wait for a command.
  void start_reporting_convergence() override {
    solver_.start_reporting_convergence();
    broadcast(Command::kReportConvergence);
  }
  bool converged_at_first_iteration() const override {
    return solver_.converged_at_first_iteration();  // PIMPLE's residuals are global
  }
  void finalize() override {
    broadcast(Command::kFinalize);
    finalized_ = true;
    solver_.finalize();
  }
  /// After serve() returned normally: lets the other ranks end, if they still wait.
  void release_others() {
    if (!started_) broadcast(Command::kExit);
  }
  bool finalized() const { return finalized_; }

 private:
  PimpleFoamSolver& solver_;
  bool started_ = false;
  bool finalized_ = false;
};

/// The other ranks: run what the master passes on until it finalizes.
void follow_master(PimpleFoamSolver& solver) {
  for (;;) {
    Foam::label code = 0;
    Foam::Pstream::scatter(code);
    Foam::scalarList values;
    Foam::Pstream::scatter(values);
    const std::vector<double> numbers(values.begin(), values.end());
    switch (static_cast<Command>(code)) {
      case Command::kInitialize:
        solver.initialize({numbers.at(0), static_cast<std::int32_t>(numbers.at(1))});
        break;
      case Command::kInitializeStep:
        solver.initialize_step(static_cast<std::int32_t>(numbers.at(0)), numbers.at(1));
        break;
      case Command::kSolve:
        try {
          solver.solve(numbers);
        } catch (const sdk::InputRejected&) {
          // The master rejects it to the coupler (the check is reduced over the ranks).
        }
        break;
      case Command::kFinalizeStep:
        solver.finalize_step();
        break;
      case Command::kOutputStep:
        solver.output_step();
        break;
      case Command::kSaveRestart:
        solver.save_restart(static_cast<std::int32_t>(numbers.at(0)));
        break;
      case Command::kReportConvergence:
        solver.start_reporting_convergence();
        break;
      case Command::kSaveState:
        solver.save_state();
        break;
      case Command::kRestoreState:
        solver.restore_state();
        break;
      case Command::kFinalizeSubstep:
        solver.finalize_substep();
        break;
      case Command::kFinalize:
        solver.finalize();
        return;
      case Command::kExit:
        return;
    }
  }
}

}  // namespace

int main(int argc, char* argv[]) {
  using namespace Foam;
  argList::addNote(
      "pimpleFoam (transient incompressible flow on a moving mesh) as a cocopp solver: the "
      "coupler gives the displacement of the interface patches and receives pressure and "
      "traction (Pa) on their faces. Started by `cocopp run` (solver type openfoam).");
  argList::addOption("patches", "(patch ...)", "the fluid-structure interface patches");
  argList::addOption("gapPatch", "patch",
                     "also output the gap of the interface faces (distance to this patch) and "
                     "the wall displacement of the interface points: what a structure driven "
                     "by displacement under a film takes");
  argList args(argc, argv);
  if (!args.checkRootCase()) FatalError.exit();
  // OpenFOAM's fatal errors become exceptions, reported to the coupler with their message.
  FatalError.throwExceptions();
  FatalIOError.throwExceptions();
  PimpleFoamSolver solver(args, args.getList<word>("patches", false),
                          args.found("gapPatch") ? args.get<word>("gapPatch") : word());
  if (!Pstream::master()) {
    try {
      follow_master(solver);
      return 0;
    } catch (const std::exception& e) {
      // The master reports to the coupler; a rank failing alone must not leave it waiting.
      std::cerr << "cocoppPimpleFoam rank " << Pstream::myProcNo() << ": " << e.what() << "\n";
      UPstream::abort();
    }
  }
  MasterSolver master(solver);
  const int status = sdk::serve(master, argc, argv);
  if (status == 0) master.release_others();
  if (status != 0 && Pstream::parRun() && !master.finalized()) UPstream::abort();  // ranks wait
  return status;
}
