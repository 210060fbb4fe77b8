// cocopp-tube-structure: the 1D tube wall with inertia (TubeStructure) as a cocopp solver
// executable.
#include <memory>

#include "solvers/tube/tube_solver.hpp"
#include "solvers/tube/tube_structure.hpp"

namespace {

constexpr const char* kUsage = R"(usage: cocopp-tube-structure [INPUT_FILE]
       cocopp-tube-structure --check [INPUT_FILE]

The wall of a 1D flexible tube (ring with inertia and bending, clamped ends), driven by the
cocopp coupler. INPUT_FILE defaults to tube_structure.yaml in the working directory.
--check reads INPUT_FILE as a run would, says what it refuses and exits (`cocopp check` asks).
Interface: model part `wall` (m points at the cell centres); input `pressure` (Pa) and
`traction` (ignored), output `displacement` (0, radial displacement, 0).

Started by the cocopp coupler (`cocopp run case.yaml`), which passes the channel in
COCOPP_TRANSPORT and COCOPP_CHANNEL; the working directory is the solver's directory.

Input file keys (SI units):
  length, diameter        tube length and diameter (> 0, required)
  cells                   number of cells m (>= 2, required)
  rho_s                   wall density (> 0, required)
  e, h                    Young's modulus and thickness of the wall (> 0, required)
  nu                      Poisson's ratio (in [0, 0.5), required)
  p_ref                   pressure at which the wall is undeformed (default 0)
  residual_atol           solver-coupling convergence: the residual of the wall equation (m) below
                          which a solve counts as converged at its first iteration (> 0;
                          needed only by the solver_coupling_convergence criterion)
  time_scheme:
    type                  backward_euler (default) | newmark
    gamma                 Newmark gamma (>= 1/2, default 1/2)
    beta                  Newmark beta (>= (1/2 + gamma)^2 / 4, default 1/4)
  output:
    interval              write output/tube_structure_<step>.vtk every N steps (0 = never)
    directory             output directory (default output)

Restarts: when the coupler saves its state the solver writes
restart/tube_structure_<step>.restart; a restarted run (timestep_start > 0) reads it back.
)";

}  // namespace

int main(int argc, char** argv) {
  using namespace cocopp::tube;
  return run_tube_solver<TubeStructure, WallSide, TubeStructureParameters>(
      argc, argv, "tube_structure", kUsage, "tube_structure.yaml",
      [](const std::string& input_file, const cocopp::sdk::RunInfo& run) {
        return std::make_unique<TubeStructure>(TubeStructureParameters::load(input_file),
                                               run.delta_t, run.timestep_start);
      });
}
