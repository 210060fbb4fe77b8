// cocopp-tube-ringmodel: the massless ring model of a 1D tube wall (TubeRingmodel) as a cocopp
// solver executable.
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include "solver_wrappers/sdk/solver_sdk.hpp"
#include "solver_wrappers/tube/tube_output.hpp"
#include "solver_wrappers/tube/tube_ringmodel.hpp"
#include "solver_wrappers/tube/wall_interface.hpp"

namespace {

constexpr const char* kUsage = R"(usage: cocopp-tube-ringmodel [INPUT_FILE]

The wall of a 1D flexible tube as independent massless rings (a tube law), driven by the
cocopp coupler. INPUT_FILE defaults to tube_ringmodel.yaml in the working directory.
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
  output:
    interval              write output/tube_ringmodel_<step>.vtk every N steps (0 = never)
    directory             output directory (default output)
)";

class TubeRingmodelSolver : public cocopp::sdk::Solver {
 public:
  explicit TubeRingmodelSolver(std::string input_file) : input_file_(std::move(input_file)) {}

  cocopp::sdk::InterfaceDescription initialize(const cocopp::sdk::RunInfo& run) override {
    rings_ = std::make_unique<cocopp::tube::TubeRingmodel>(
        cocopp::tube::TubeRingmodelParameters::load(input_file_), run.timestep_start);
    rings_->output_step(rings_->step());
    cocopp::sdk::InterfaceDescription description;
    description.model_parts.push_back(cocopp::tube::wall_model_part(
        rings_->parameters().geometry, {"pressure", "traction"}, {"displacement"}));
    description.initial_output =
        cocopp::tube::to_vector(cocopp::tube::radial_vectors(rings_->displacement()));
    return description;
  }

  void initialize_step(std::int32_t step, double /*time*/) override {
    rings_->initialize_step();
    if (step != rings_->step()) {
      throw std::runtime_error("tube ring model: the coupler started step " + std::to_string(step) +
                               ", expected step " + std::to_string(rings_->step()));
    }
  }

  // Input: m pressures, then m traction vectors (ignored).
  std::vector<double> solve(const std::vector<double>& input) override {
    const int m = rings_->cells();
    if (input.size() != 4 * static_cast<std::size_t>(m)) {
      throw std::runtime_error("tube ring model: interface input has " +
                               std::to_string(input.size()) + " values, expected " +
                               std::to_string(4 * m));
    }
    const Eigen::VectorXd pressure = Eigen::Map<const Eigen::VectorXd>(input.data(), m);
    return cocopp::tube::to_vector(cocopp::tube::radial_vectors(rings_->solve(pressure)));
  }

  void finalize_step() override { rings_->finalize_step(); }
  void output_step() override { rings_->output_step(rings_->step()); }

 private:
  std::string input_file_;
  std::unique_ptr<cocopp::tube::TubeRingmodel> rings_;
};

}  // namespace

int main(int argc, char** argv) {
  if (cocopp::tube::wants_help(argc, argv)) {
    std::cout << kUsage;
    return 0;
  }
  TubeRingmodelSolver solver(cocopp::tube::input_file_argument(argc, argv, "tube_ringmodel.yaml"));
  return cocopp::sdk::serve(solver, argc, argv);
}
