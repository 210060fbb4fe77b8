// cocopp-tube-flow: the 1D tube flow solver (TubeFlow) as a cocopp solver executable.
#include <memory>

#include "solvers/tube/tube_flow.hpp"
#include "solvers/tube/tube_solver.hpp"

namespace {

constexpr const char* kUsage = R"(usage: cocopp-tube-flow [INPUT_FILE]
       cocopp-tube-flow --check [INPUT_FILE]

1D incompressible, inviscid flow in a flexible tube, driven by the cocopp coupler.
INPUT_FILE defaults to tube_flow.yaml in the working directory.
--check reads INPUT_FILE as a run would, says what it refuses and exits (`cocopp check` asks).
Interface: model part `wall` (m points at the cell centres); input `displacement` (the y
component is the radial displacement), output `pressure` (Pa) and `traction` (zero).

Started by the cocopp coupler (`cocopp run case.yaml`), which passes the channel in
COCOPP_TRANSPORT and COCOPP_CHANNEL; the working directory is the solver's directory.

Input file keys (SI units):
  length, diameter        tube length and diameter (> 0, required)
  cells                   number of cells m (>= 2, required)
  rho_f                   fluid density (> 0, required)
  e, h                    Young's modulus and thickness of the wall (> 0, required)
  u_ref                   reference velocity of the pressure stabilisation (>= 0, required)
  u0                      initial velocity (default 0)
  p_ref                   initial pressure (default 0)
  inlet:
    boundary              pressure | velocity | total_pressure (required)
    variable              sine | pulse | sin2 | constant | ramp (required)
    reference             value = reference + function (default 0)
    amplitude             amplitude A of the function (required)
    period                period T (> 0, required except for constant)
  outlet:
    boundary              fixed | non_reflecting (required)
    pressure              outlet pressure of a fixed outlet (default 0)
  newtonmax               maximum Newton steps per coupling iteration (>= 1, required)
  newtontol               relative residual at which Newton stops (> 0, required)
  output:
    interval              write output/tube_flow_<step>.vtk every N steps (0 = never, default)
    directory             output directory (default output)

Restarts: when the coupler saves its state the solver writes
restart/tube_flow_<step>.restart; a restarted run (timestep_start > 0) reads it back.
)";

}  // namespace

int main(int argc, char** argv) {
  using namespace cocopp::tube;
  return run_tube_solver<TubeFlow, FlowSide, TubeFlowParameters>(
      argc, argv, "tube_flow", kUsage, "tube_flow.yaml",
      [](const std::string& input_file, const cocopp::sdk::RunInfo& run) {
        return std::make_unique<TubeFlow>(TubeFlowParameters::load(input_file), run.delta_t,
                                          run.timestep_start);
      });
}
