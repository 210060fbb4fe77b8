#pragma once
// In-process solver wrappers for testing coupled solvers: an affine "flow" y = A x + b and an
// affine "structure" x = B y, on one model part of n points. The coupled problem
// x = B (A x + b) has the exact solution x* = (I - B A)^-1 B b.
#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <limits>

#include "solver_wrappers/solver_wrapper.hpp"

namespace cocopp::testing {

inline std::shared_ptr<const ModelPart> line_model_part(int n) {
  auto part = std::make_shared<ModelPart>();
  part->name = "wall";
  part->coordinates = Coordinates::Zero(n, 3);
  for (int i = 0; i < n; ++i) {
    part->ids.push_back(i);
    part->coordinates(i, 2) = i;
  }
  return part;
}

/// The parts every in-process test solver shares: a name, fixed interfaces, no-op steps.
class InProcessSolver : public SolverWrapper {
 public:
  InProcessSolver(std::string name, Interface input, Interface output)
      : name_(std::move(name)), input_(std::move(input)), output_(std::move(output)) {}

  const std::string& name() const override { return name_; }
  void initialize() override {}
  const Interface& input_interface() const override { return input_; }
  const Interface& output_interface() const override { return output_; }
  void initialize_step(int step, double) override { step_ = step; }
  void finalize_step() override {}
  void output_step() override {}
  void finalize() override {}

 protected:
  std::string name_;
  Interface input_, output_;
  int step_ = 0;
};

/// Maps `input_variable` to `output_variable` affinely on the first component.
class AffineSolver : public InProcessSolver {
 public:
  AffineSolver(std::string name, std::shared_ptr<const ModelPart> part, std::string input,
               std::string output, Eigen::MatrixXd matrix, Eigen::VectorXd offset)
      : InProcessSolver(std::move(name), Interface({{part, {std::move(input)}}}),
                        Interface({{part, {std::move(output)}}})),
        matrix_(std::move(matrix)),
        offset_(std::move(offset)) {}

  const Interface& solve(const Interface& input) override {
    ++calls;
    const auto& in_block = input.blocks().front();
    const auto in = input.values(in_block.model_part, in_block.variable);
    const Eigen::VectorXd result = matrix_ * Eigen::VectorXd(in.col(in.cols() > 1 ? 1 : 0)) +
                                   (1.0 + offset_variation * std::sin(step_)) * offset_;
    const auto& out_block = output_.blocks().front();
    auto out = output_.values(out_block.model_part, out_block.variable);
    out.setZero();
    out.col(out.cols() > 1 ? 1 : 0) = result;
    if (poison_at_call == calls) out(0, 0) = std::numeric_limits<double>::quiet_NaN();
    return output_;
  }

  int calls = 0;
  int poison_at_call = -1;  ///< return NaN at this call
  /// offset times (1 + offset_variation sin(step)): a solution no predictor foresees exactly
  double offset_variation = 0.0;

 private:
  Eigen::MatrixXd matrix_;
  Eigen::VectorXd offset_;
};

/// output = matrix * input + offset on the whole flattened interface vectors, whatever their
/// variables: for problems whose interfaces carry several variables.
class FlatAffineSolver : public InProcessSolver {
 public:
  FlatAffineSolver(std::string name, Interface input, Interface output, Eigen::MatrixXd matrix,
                   Eigen::VectorXd offset)
      : InProcessSolver(std::move(name), std::move(input), std::move(output)),
        matrix_(std::move(matrix)),
        offset_(std::move(offset)) {}

  const Interface& solve(const Interface& input) override {
    output_.set_data(matrix_ * input.data() + offset_);
    return output_;
  }

 private:
  Eigen::MatrixXd matrix_;
  Eigen::VectorXd offset_;
};

}  // namespace cocopp::testing
