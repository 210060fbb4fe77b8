#pragma once
// The SDK face shared by the three tube solver executables: TubeSolver<Model, Side> drives a
// tube model (TubeFlow, TubeStructure, TubeRingmodel) through the cocopp protocol; `Side` says
// which way the interface data goes (FlowSide: displacement in, loads out; WallSide: loads in,
// displacement out).
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/data/restart_file.hpp"
#include "solvers/sdk/solver_sdk.hpp"
#include "solvers/tube/tube_output.hpp"
#include "solvers/tube/wall_interface.hpp"

namespace cocopp::tube {

/// Displacement in (its y component is the radial displacement); pressure and a zero traction
/// (inviscid flow) out.
struct FlowSide {
  static std::vector<std::string> inputs() { return {"displacement"}; }
  static std::vector<std::string> outputs() { return {"pressure", "traction"}; }
  template <class Model>
  static void solve(Model& model, const std::vector<double>& input) {
    model.solve(radial_component(input, model.cells()));
  }
  template <class Model>
  static std::vector<double> output(const Model& model) {
    std::vector<double> values = to_vector(model.pressure());
    values.resize(values.size() + 3 * static_cast<std::size_t>(model.cells()), 0.0);
    return values;
  }
};

/// Pressure and traction in (the wall only feels pressure); displacement (0, dr, 0) out.
struct WallSide {
  static std::vector<std::string> inputs() { return {"pressure", "traction"}; }
  static std::vector<std::string> outputs() { return {"displacement"}; }
  template <class Model>
  static void solve(Model& model, const std::vector<double>& input) {
    const int m = model.cells();
    if (input.size() != 4 * static_cast<std::size_t>(m))
      throw std::runtime_error("interface input has " + std::to_string(input.size()) +
                               " values, expected " + std::to_string(4 * m));
    model.solve(Eigen::Map<const Eigen::VectorXd>(input.data(), m));
  }
  template <class Model>
  static std::vector<double> output(const Model& model) {
    return to_vector(radial_vectors(model.displacement()));
  }
};

template <class Model, class Side>
class TubeSolver : public sdk::Solver {
 public:
  /// Builds the model once the coupler has sent the time step.
  using Factory = std::function<std::unique_ptr<Model>(const sdk::RunInfo&)>;
  /// `name` ("tube_flow", ...) names its restart files.
  TubeSolver(std::string name, Factory make) : name_(std::move(name)), make_(std::move(make)) {}

  sdk::InterfaceDescription initialize(const sdk::RunInfo& run) override {
    model_ = make_(run);
    delta_t_ = run.delta_t;
    if (run.timestep_start > 0) {
      const auto file = restart_file_name(name_, run.timestep_start);
      model_->restore(read_restart_file(file, name_, run.timestep_start),
                      std::filesystem::absolute(file));
    } else {
      output();
    }
    sdk::InterfaceDescription description;
    description.model_parts.push_back(
        wall_model_part(model_->parameters().geometry, Side::inputs(), Side::outputs()));
    description.initial_output = Side::output(*model_);
    return description;
  }

  void initialize_step(std::int32_t step, double /*time*/) override {
    model_->initialize_step();
    if (step != model_->step())
      throw std::runtime_error("the coupler started step " + std::to_string(step) +
                               ", expected step " + std::to_string(model_->step()));
  }

  std::vector<double> solve(const std::vector<double>& input) override {
    Side::solve(*model_, input);
    return Side::output(*model_);
  }

  void start_reporting_convergence() override { model_->start_reporting_convergence(); }
  bool converged_at_first_iteration() const override {
    return model_->converged_at_first_iteration();
  }
  void finalize_step() override { model_->finalize_step(); }
  void output_step() override { output(); }

  // Substeps: the model's whole state, step counter included, is a copy away.
  bool can_substep() const override { return true; }
  void save_state() override { saved_ = std::make_unique<Model>(*model_); }
  void restore_state() override { *model_ = *saved_; }

  bool can_restart() const override { return true; }
  void save_restart(std::int32_t step) override {
    if (step != model_->step())
      throw std::runtime_error("the coupler asked for the restart data of step " +
                               std::to_string(step) + ", the solver is at step " +
                               std::to_string(model_->step()));
    write_restart_file(restart_file_name(name_, step), name_, step, model_->restart_data());
  }

 private:
  void output() const { model_->output_step(model_->step(), model_->step() * delta_t_); }

  std::string name_;
  Factory make_;
  std::unique_ptr<Model> model_;
  std::unique_ptr<Model> saved_;  ///< the window's start (substeps)
  double delta_t_ = 0.0;
};

/// `--check [INPUT_FILE]`: read the input file as a run would and say what is wrong (exit 1)
/// or that it is fine (exit 0); `cocopp check` asks the solver so.
template <class Parameters>
int check_input_file(const std::string& input_file) {
  try {
    (void)Parameters::load(input_file);
  } catch (const std::exception& error) {
    std::cerr << error.what() << "\n";
    return 1;
  }
  std::cout << input_file << ": OK\n";
  return 0;
}

/// main() of a tube solver executable: --help prints `usage`, --check checks the input file
/// (check_input_file), else serve the coupler with the model `make` builds from the input file
/// (argv[1] or `default_input`).
template <class Model, class Side, class Parameters, class Make>
int run_tube_solver(int argc, char** argv, const std::string& name, const char* usage,
                    const std::string& default_input, Make make) {
  if (sdk::wants_help(argc, argv)) {
    std::cout << usage;
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "--check")
    return check_input_file<Parameters>(argc > 2 ? argv[2] : default_input);
  const std::string input_file = input_file_argument(argc, argv, default_input);
  TubeSolver<Model, Side> solver(
      name, [input_file, make](const sdk::RunInfo& run) { return make(input_file, run); });
  return sdk::serve(solver, argc, argv);
}

}  // namespace cocopp::tube
