// cocopp-tube-structure: the 1D tube wall with inertia (TubeStructure) as a cocopp solver
// executable.
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include "solver_wrappers/sdk/solver_sdk.hpp"
#include "solver_wrappers/tube/tube_output.hpp"
#include "solver_wrappers/tube/tube_structure.hpp"
#include "solver_wrappers/tube/wall_interface.hpp"

namespace {

constexpr const char* kUsage = R"(usage: cocopp-tube-structure [INPUT_FILE]

The wall of a 1D flexible tube (ring with inertia and bending, clamped ends), driven by the
cocopp coupler. INPUT_FILE defaults to tube_structure.yaml in the working directory.
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
  time_scheme:
    type                  backward_euler (default) | newmark
    gamma                 Newmark gamma (>= 1/2, default 1/2)
    beta                  Newmark beta (>= (1/2 + gamma)^2 / 4, default 1/4)
  output:
    interval              write output/tube_structure_<step>.vtk every N steps (0 = never)
    directory             output directory (default output)
)";

class TubeStructureSolver : public cocopp::sdk::Solver {
 public:
  explicit TubeStructureSolver(std::string input_file) : input_file_(std::move(input_file)) {}

  cocopp::sdk::InterfaceDescription initialize(const cocopp::sdk::RunInfo& run) override {
    structure_ = std::make_unique<cocopp::tube::TubeStructure>(
        cocopp::tube::TubeStructureParameters::load(input_file_), run.delta_t, run.timestep_start);
    structure_->output_step(structure_->step());
    cocopp::sdk::InterfaceDescription description;
    description.model_parts.push_back(cocopp::tube::wall_model_part(
        structure_->parameters().geometry, {"pressure", "traction"}, {"displacement"}));
    description.initial_output =
        cocopp::tube::to_vector(cocopp::tube::radial_vectors(structure_->displacement()));
    return description;
  }

  void initialize_step(std::int32_t step, double /*time*/) override {
    structure_->initialize_step();
    if (step != structure_->step()) {
      throw std::runtime_error("tube structure: the coupler started step " + std::to_string(step) +
                               ", expected step " + std::to_string(structure_->step()));
    }
  }

  // Input: m pressures, then m traction vectors (ignored: the wall only feels pressure).
  std::vector<double> solve(const std::vector<double>& input) override {
    const int m = structure_->cells();
    if (input.size() != 4 * static_cast<std::size_t>(m)) {
      throw std::runtime_error("tube structure: interface input has " +
                               std::to_string(input.size()) + " values, expected " +
                               std::to_string(4 * m));
    }
    const Eigen::VectorXd pressure = Eigen::Map<const Eigen::VectorXd>(input.data(), m);
    return cocopp::tube::to_vector(cocopp::tube::radial_vectors(structure_->solve(pressure)));
  }

  void finalize_step() override { structure_->finalize_step(); }
  void output_step() override { structure_->output_step(structure_->step()); }

 private:
  std::string input_file_;
  std::unique_ptr<cocopp::tube::TubeStructure> structure_;
};

}  // namespace

int main(int argc, char** argv) {
  if (cocopp::tube::wants_help(argc, argv)) {
    std::cout << kUsage;
    return 0;
  }
  TubeStructureSolver solver(cocopp::tube::input_file_argument(argc, argv, "tube_structure.yaml"));
  return cocopp::sdk::serve(solver, argc, argv);
}
