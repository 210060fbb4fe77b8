// cocopp-tube-ringmodel: the massless ring model of a 1D tube wall (TubeRingmodel) as a cocopp
// solver executable.
#include <memory>

#include "solvers/tube/tube_ringmodel.hpp"
#include "solvers/tube/tube_solver.hpp"

namespace {

constexpr const char* kUsage = R"(usage: cocopp-tube-ringmodel [INPUT_FILE]
       cocopp-tube-ringmodel --check [INPUT_FILE]

The wall of a 1D flexible tube as independent massless rings (a tube law), driven by the
cocopp coupler. INPUT_FILE defaults to tube_ringmodel.yaml in the working directory.
--check reads INPUT_FILE as a run would, says what it refuses and exits (`cocopp check` asks).
Interface: model part `wall` (m points at the cell centres); input `pressure` (Pa) and
`traction` (ignored), output `displacement` (0, radial displacement, 0).

Started by the cocopp coupler (`cocopp run case.yaml`), which passes the channel in
COCOPP_TRANSPORT and COCOPP_CHANNEL; the working directory is the solver's directory.

Input file keys (SI units):
  length, diameter        tube length and diameter (> 0, required)
  cells                   number of cells m (>= 2, required)
  rho_f                   fluid density (> 0, required)
  e, h                    Young's modulus and thickness of the wall (> 0, required)
  p_ref                   pressure at which the wall is undeformed (default 0)
  residual_atol           solver-coupling convergence: the change of the displacement (m) below
                          which a solve counts as converged at its first iteration (> 0;
                          needed only by the solver_coupling_convergence criterion)
  output:
    interval              write output/tube_ringmodel_<step>.vtk every N steps (0 = never)
    directory             output directory (default output)

Restarts: when the coupler saves its state the solver writes
restart/tube_ringmodel_<step>.restart; a restarted run (timestep_start > 0) reads it back.
)";

}  // namespace

int main(int argc, char** argv) {
  using namespace cocopp::tube;
  return run_tube_solver<TubeRingmodel, WallSide, TubeRingmodelParameters>(
      argc, argv, "tube_ringmodel", kUsage, "tube_ringmodel.yaml",
      [](const std::string& input_file, const cocopp::sdk::RunInfo& run) {
        return std::make_unique<TubeRingmodel>(TubeRingmodelParameters::load(input_file),
                                               run.timestep_start);
      });
}
