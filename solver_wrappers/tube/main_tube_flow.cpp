// cocopp-tube-flow: the 1D tube flow solver (TubeFlow) as a cocopp solver executable.
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include "solver_wrappers/sdk/solver_sdk.hpp"
#include "solver_wrappers/tube/tube_flow.hpp"
#include "solver_wrappers/tube/wall_interface.hpp"

namespace {

constexpr const char* kUsage = R"(usage: cocopp-tube-flow [INPUT_FILE]

1D incompressible, inviscid flow in a flexible tube, driven by the cocopp coupler.
INPUT_FILE defaults to tube_flow.yaml in the working directory.
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
)";

class TubeFlowSolver : public cocopp::sdk::Solver {
 public:
  explicit TubeFlowSolver(std::string input_file) : input_file_(std::move(input_file)) {}

  cocopp::sdk::InterfaceDescription initialize(const cocopp::sdk::RunInfo& run) override {
    flow_ = std::make_unique<cocopp::tube::TubeFlow>(
        cocopp::tube::TubeFlowParameters::load(input_file_), run.delta_t, run.timestep_start);
    flow_->output_step(flow_->step());
    const auto& geometry = flow_->parameters().geometry;
    cocopp::sdk::InterfaceDescription description;
    description.model_parts.push_back(
        cocopp::tube::wall_model_part(geometry, {"displacement"}, {"pressure", "traction"}));
    description.initial_output = output_values();
    return description;
  }

  void initialize_step(std::int32_t step, double /*time*/) override {
    flow_->initialize_step();
    if (step != flow_->step()) {
      throw std::runtime_error("tube flow: the coupler started step " + std::to_string(step) +
                               ", expected step " + std::to_string(flow_->step()));
    }
  }

  std::vector<double> solve(const std::vector<double>& input) override {
    flow_->solve(cocopp::tube::radial_component(input, flow_->cells()));
    return output_values();
  }

  void finalize_step() override { flow_->finalize_step(); }
  void output_step() override { flow_->output_step(flow_->step()); }

 private:
  // Pressure of every point, then a zero traction vector per point (inviscid flow).
  std::vector<double> output_values() const {
    std::vector<double> values = cocopp::tube::to_vector(flow_->pressure());
    values.resize(values.size() + 3 * static_cast<std::size_t>(flow_->cells()), 0.0);
    return values;
  }

  std::string input_file_;
  std::unique_ptr<cocopp::tube::TubeFlow> flow_;
};

}  // namespace

int main(int argc, char** argv) {
  if (cocopp::tube::wants_help(argc, argv)) {
    std::cout << kUsage;
    return 0;
  }
  TubeFlowSolver solver(cocopp::tube::input_file_argument(argc, argv, "tube_flow.yaml"));
  return cocopp::sdk::serve(solver, argc, argv);
}
