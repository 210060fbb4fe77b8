// cocoppPimpleFoam: pimpleFoam with a moving mesh, driven by the cocopp coupler. It stays
// running for the whole simulation; see pimple_foam_solver.hpp for what one step and one
// coupling iteration do, and docs/solver-wrappers-openfoam.md for the case set-up.
//
//   cocoppPimpleFoam -patches '(wall)'        (started by `cocopp run`, in the case directory)
#include "solver_wrappers/openfoam/pimple_foam_solver.hpp"

int main(int argc, char* argv[]) {
  using namespace Foam;
  argList::addNote(
      "pimpleFoam (transient incompressible flow on a moving mesh) as a cocopp solver: the "
      "coupler gives the displacement of the interface patches and receives pressure and "
      "traction (Pa) on their faces. Started by `cocopp run` (solver type openfoam).");
  argList::noParallel();
  argList::addOption("patches", "(patch ...)", "the fluid-structure interface patches");
  argList args(argc, argv);
  if (!args.checkRootCase()) FatalError.exit();
  // OpenFOAM's fatal errors become exceptions, reported to the coupler with their message.
  FatalError.throwExceptions();
  FatalIOError.throwExceptions();
  cocopp::openfoam::PimpleFoamSolver solver(args, args.getList<word>("patches", false));
  return cocopp::sdk::serve(solver, argc, argv);
}
