// iqnism (IQN-ILSM): IQN-ILS with the secant model of a surrogate coupled problem, on affine
// problems whose exact solution is known. The surrogate's solvers come from the case's
// settings like any solver wrapper: here a registered test type that forwards to an affine
// solver built by the test.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <map>

#include "coupler/coupled_solvers/coupled_solver.hpp"
#include "coupler/results/state_file.hpp"
#include "tests/support/error_message.hpp"
#include "tests/support/linear_solvers.hpp"

using namespace cocopp;
using cocopp::testing::AffineSolver;

namespace {

/// The solvers a test built, by the name the case file gives them.
std::map<std::string, SolverWrapper*>& test_solvers() {
  static std::map<std::string, SolverWrapper*> solvers;
  return solvers;
}

/// Solver wrapper type `test_solver`: forwards every call to test_solvers()[solver].
class ForwardingSolver : public SolverWrapper {
 public:
  ForwardingSolver(const Settings& s, const RunSettings&)
      : target_(*test_solvers().at(s.required<std::string>("solver"))) {}
  const std::string& name() const override { return target_.name(); }
  void initialize() override { target_.initialize(); }
  const Interface& input_interface() const override { return target_.input_interface(); }
  const Interface& output_interface() const override { return target_.output_interface(); }
  void initialize_step(int step, double time) override { target_.initialize_step(step, time); }
  const Interface& solve(const Interface& input) override { return target_.solve(input); }
  void finalize_step() override { target_.finalize_step(); }
  void output_step() override { target_.output_step(); }
  void finalize() override { target_.finalize(); }

 private:
  SolverWrapper& target_;
};

COCOPP_REGISTER(SolverWrapperRegistry, "test_solver", ForwardingSolver)

/// x = B (A x + b) with A = 2 I and B A = Q diag(eigenvalues) Q^T for a random orthogonal Q
/// (seeded by `seed`): Gauss-Seidel diverges for eigenvalues below -1.
struct AffineProblem {
  AffineProblem(const std::string& prefix, int n, double low, double high, unsigned seed)
      : part(cocopp::testing::line_model_part(n)) {
    std::srand(seed);
    const Eigen::MatrixXd q = Eigen::MatrixXd::Random(n, n).householderQr().householderQ();
    const Eigen::MatrixXd coupling =
        q * Eigen::VectorXd::LinSpaced(n, low, high).asDiagonal() * q.transpose();
    const Eigen::VectorXd offset = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
    flow = std::make_unique<AffineSolver>(prefix + "flow", part, "displacement", "pressure",
                                          2.0 * Eigen::MatrixXd::Identity(n, n), offset);
    structure =
        std::make_unique<AffineSolver>(prefix + "structure", part, "pressure", "displacement",
                                       coupling / 2.0, Eigen::VectorXd::Zero(n));
    flow->offset_variation = 0.3;  // every step a solution no predictor foresees
    test_solvers()[prefix + "flow"] = flow.get();
    test_solvers()[prefix + "structure"] = structure.get();
  }
  std::shared_ptr<const ModelPart> part;
  std::unique_ptr<AffineSolver> flow, structure;
};

const char* kCriterion =
    "predictor: {type: constant}\n"
    "convergence_criterion:\n"
    "  type: or\n"
    "  criteria:\n"
    "    - {type: absolute_norm, tolerance: 1e-10}\n"
    "    - {type: iteration_limit, maximum: 100}\n";

/// An iqnism case: the model `ls` without reuse, the surrogate iqni (ls, `surrogate_q`) on the
/// test solvers "s_flow" and "s_structure", plus `extra` surrogate settings.
std::unique_ptr<CoupledSolver> make_iqnism(const std::string& extra = "", int surrogate_q = 0) {
  const std::string yaml = std::string("type: iqnism\nomega: 0.05\nmodel: {type: ls, q: 0}\n") +
                           kCriterion + "surrogate:\n" + extra +
                           "  coupled_solver:\n"
                           "    type: iqni\n"
                           "    omega: 0.05\n"
                           "    model: {type: ls, q: " +
                           std::to_string(surrogate_q) +
                           "}\n"
                           "    predictor: {type: constant}\n"
                           "    convergence_criterion:\n"
                           "      type: or\n"
                           "      criteria:\n"
                           "        - {type: absolute_norm, tolerance: 1e-12}\n"
                           "        - {type: iteration_limit, maximum: 100}\n"
                           "  solver_wrappers:\n"
                           "    - {type: test_solver, solver: s_flow}\n"
                           "    - {type: test_solver, solver: s_structure}\n";
  const Settings settings = Settings::load_string(yaml, "case.yaml");
  auto coupled = CoupledSolverRegistry::instance().create(settings);
  coupled->create_own_solvers(RunSettings{});
  settings.check_unused_keys();
  return coupled;
}

std::unique_ptr<CoupledSolver> make_iqni() {
  return CoupledSolverRegistry::instance().create(Settings::load_string(
      std::string("type: iqni\nomega: 0.05\nmodel: {type: ls, q: 0}\n") + kCriterion, "case.yaml"));
}

/// Iterations per step of `steps` steps of `coupled` on `problem`.
std::vector<int> iterations(CoupledSolver& coupled, AffineProblem& problem, int steps) {
  coupled.initialize(*problem.flow, *problem.structure);
  std::vector<int> counts;
  for (int step = 1; step <= steps; ++step) {
    const StepRecord record = coupled.solve_step(step, 0.1 * step);
    EXPECT_TRUE(record.converged) << "step " << step;
    counts.push_back(record.iterations);
  }
  return counts;
}

int total(const std::vector<int>& counts) {
  int sum = 0;
  for (int count : counts) sum += count;
  return sum;
}

}  // namespace

// With the surrogate the same problem, its secant model after its own step spans the residual's
// Krylov space, in which the real residual lies too (both start from the same x): the first
// quasi-Newton update is Newton's, and every step converges in its second iteration. IQN-ILS
// alone needs about n + 1 = 7.
TEST(Iqnism, AnExactSurrogateConvergesInTwoIterations) {
  AffineProblem real("", 6, -3.0, -1.5, 7), surrogate("s_", 6, -3.0, -1.5, 7);
  auto coupled = make_iqnism();
  const std::vector<int> with = iterations(*coupled, real, 4);
  for (int count : with) EXPECT_LE(count, 2);
  AffineProblem again("", 6, -3.0, -1.5, 7);
  const std::vector<int> without = iterations(*make_iqni(), again, 4);
  for (int count : without) EXPECT_GE(count, 6);
}

// The surrogate's solution as the step's first x: with an exact surrogate it is the solution.
TEST(Iqnism, AnExactSurrogatesSolutionIsTheFirstInput) {
  AffineProblem real("", 6, -3.0, -1.5, 7), surrogate("s_", 6, -3.0, -1.5, 7);
  auto coupled = make_iqnism("  prediction: value\n");
  for (int count : iterations(*coupled, real, 3)) EXPECT_EQ(count, 1);
}

// A poor surrogate: another coupling matrix (other eigenvectors, eigenvalues from -2 to -0.5
// instead of -3 to -1.5). The model's own columns take over, and the method converges in no
// more iterations than IQN-ILS alone.
TEST(Iqnism, APoorSurrogateIsNoWorseThanIqnIls) {
  AffineProblem real("", 8, -3.0, -1.5, 7), surrogate("s_", 8, -2.0, -0.5, 99);
  const std::vector<int> with = iterations(*make_iqnism(), real, 5);
  AffineProblem again("", 8, -3.0, -1.5, 7);
  const std::vector<int> without = iterations(*make_iqni(), again, 5);
  std::printf("poor surrogate: %d iterations in 5 steps, IQN-ILS alone %d\n", total(with),
              total(without));
  EXPECT_LE(total(with), total(without));
}

TEST(Iqnism, TheSurrogateMustHaveTheCasesInterface) {
  AffineProblem real("", 6, -3.0, -1.5, 7), surrogate("s_", 5, -3.0, -1.5, 7);
  auto coupled = make_iqnism();
  const std::string message = cocopp::testing::error_message<std::exception>(
      [&] { coupled->initialize(*real.flow, *real.structure); });
  EXPECT_NE(message.find("the surrogate's interface"), std::string::npos) << message;
  EXPECT_NE(message.find("surrogate.mapper"), std::string::npos) << message;
}

TEST(Iqnism, ConfigurationErrorsSayWhatToChange) {
  AffineProblem real("", 4, -3.0, -1.5, 7), surrogate("s_", 4, -3.0, -1.5, 7);
  const std::string model = cocopp::testing::error_message<std::exception>([] {
    CoupledSolverRegistry::instance().create(Settings::load_string(
        std::string("type: iqnism\nmodel: {type: mv}\nsurrogate: {}\n") + kCriterion, "case.yaml"));
  });
  EXPECT_NE(model.find("needs a model that fits residuals ('ls')"), std::string::npos) << model;
  const std::string surrogate_type = cocopp::testing::error_message<std::exception>([] {
    const std::string yaml = std::string("type: iqnism\nmodel: {type: ls}\n") + kCriterion +
                             "surrogate:\n  coupled_solver:\n    type: aitken\n" +
                             "    predictor: {type: constant}\n" +
                             "    convergence_criterion: {type: iteration_limit, maximum: 3}\n" +
                             "  solver_wrappers: []\n";
    auto coupled =
        CoupledSolverRegistry::instance().create(Settings::load_string(yaml, "case.yaml"));
    coupled->create_own_solvers(RunSettings{});
  });
  EXPECT_NE(surrogate_type.find("must be 'iqni' without scaling"), std::string::npos)
      << surrogate_type;
}

// A surrogate close to the real problem (the same eigenvectors, eigenvalues 20 % smaller)
// saves iterations: its Jacobian is wrong, but less so than Gauss-Seidel's step.
TEST(Iqnism, ANearbySurrogateSavesIterations) {
  AffineProblem real("", 8, -3.0, -1.5, 7), surrogate("s_", 8, -2.4, -1.2, 7);
  const std::vector<int> with = iterations(*make_iqnism(), real, 5);
  AffineProblem again("", 8, -3.0, -1.5, 7);
  const std::vector<int> without = iterations(*make_iqni(), again, 5);
  std::printf("nearby surrogate: %d iterations in 5 steps, IQN-ILS alone %d\n", total(with),
              total(without));
  EXPECT_LT(total(with), total(without));
}

// A run split in two through the state file (the model's columns, the surrogate's own state
// and its last solution) continues as the uninterrupted run.
TEST(Iqnism, ContinuesFromItsSavedState) {
  const char* settings = "  prediction: change\n";
  auto make = [&] { return make_iqnism(settings, 10); };
  AffineProblem whole("", 6, -3.0, -1.5, 7), whole_surrogate("s_", 6, -2.4, -1.2, 7);
  auto uninterrupted = make();
  const std::vector<int> expected = iterations(*uninterrupted, whole, 6);
  const Eigen::VectorXd expected_x = uninterrupted->x().data();

  const auto file = std::filesystem::temp_directory_path() /
                    ("cocopp_test_iqnism_" + std::to_string(::getpid()) + ".h5");
  {
    AffineProblem first("", 6, -3.0, -1.5, 7), first_surrogate("s_", 6, -2.4, -1.2, 7);
    auto first_half = make();
    EXPECT_EQ(iterations(*first_half, first, 3),
              std::vector<int>(expected.begin(), expected.begin() + 3));
    SavedState saved;
    saved.step = 3;
    first_half->save_state(saved.state);
    write_state_file(file, saved);
  }
  AffineProblem second("", 6, -3.0, -1.5, 7), second_surrogate("s_", 6, -2.4, -1.2, 7);
  auto second_half = make();
  second_half->initialize(*second.flow, *second.structure);
  second_half->load_state(read_state_file(file).state);
  std::filesystem::remove(file);
  for (int step = 4; step <= 6; ++step) {
    const StepRecord record = second_half->solve_step(step, 0.1 * step);
    EXPECT_EQ(record.iterations, expected[std::size_t(step - 1)]) << "step " << step;
  }
  EXPECT_LT((second_half->x().data() - expected_x).norm(), 1e-12 * expected_x.norm());
}

// A surrogate whose own coupling diverges stops the run with a message that says it was the
// surrogate's (its filter drops every secant column, which leaves Gauss-Seidel, omega 1, on a
// problem with eigenvalues below -1).
TEST(Iqnism, ASurrogateThatDivergesSaysSo) {
  AffineProblem real("", 4, -3.0, -1.5, 7), surrogate("s_", 4, -3.0, -1.5, 7);
  const std::string yaml =
      std::string("type: iqnism\nmodel: {type: ls}\n") + kCriterion +
      "surrogate:\n  coupled_solver:\n    type: iqni\n    omega: 1\n"
      "    model: {type: ls, min_significant: 1.0e+300}\n    predictor: {type: constant}\n"
      "    divergence: {factor: 10}\n"
      "    convergence_criterion: {type: iteration_limit, maximum: 50}\n"
      "  solver_wrappers:\n"
      "    - {type: test_solver, solver: s_flow}\n"
      "    - {type: test_solver, solver: s_structure}\n";
  auto coupled = CoupledSolverRegistry::instance().create(Settings::load_string(yaml, "case.yaml"));
  coupled->create_own_solvers(RunSettings{});
  coupled->initialize(*real.flow, *real.structure);
  const std::string message =
      cocopp::testing::error_message<DivergenceError>([&] { coupled->solve_step(1, 0.1); });
  EXPECT_NE(message.find("iqnism's surrogate: the coupling diverged in time step 1"),
            std::string::npos)
      << message;
}

// The mapper keys: one 'mapper' both ways, or both one-way mappers, never a half pair.
TEST(Iqnism, AOneWayMapperNeedsItsCounterpart) {
  const std::string message = cocopp::testing::error_message<std::exception>([] {
    CoupledSolverRegistry::instance().create(Settings::load_string(
        std::string("type: iqnism\nmodel: {type: ls}\n") + kCriterion +
            "surrogate:\n  mapper_to_surrogate: {type: linear, directions: [z]}\n",
        "case.yaml"));
  });
  EXPECT_NE(message.find("needs its counterpart 'mapper_from_surrogate'"), std::string::npos)
      << message;
  EXPECT_NE(message.find("case.yaml:"), std::string::npos) << message;
}

// The step's first update before the model has columns: what the surrogate's columns do not
// explain is relaxed by omega, x + omega r on that part. The surrogate here only ever moves
// along the first point (its offset and its coupling act there alone), so its columns span
// that direction; on the second point the update must be exactly relaxation: x_2 = omega r_1
// from x_1 = 0, where a wrong sign would give (2 - omega) r_1.
TEST(Iqnism, WhatTheSurrogateDoesNotExplainIsRelaxedByOmega) {
  class RecordingFlow : public AffineSolver {
   public:
    using AffineSolver::AffineSolver;
    const Interface& solve(const Interface& input) override {
      inputs.push_back(input.values("wall", "displacement").col(1));
      return AffineSolver::solve(input);
    }
    std::vector<Eigen::VectorXd> inputs;
  };
  const auto part = cocopp::testing::line_model_part(2);
  const Eigen::Matrix2d two = 2.0 * Eigen::Matrix2d::Identity();
  RecordingFlow flow("flow", part, "displacement", "pressure", two, Eigen::Vector2d(1.0, 1.0));
  AffineSolver structure("structure", part, "pressure", "displacement",
                         Eigen::Vector2d(-0.75, -0.75).asDiagonal().toDenseMatrix(),
                         Eigen::Vector2d::Zero());
  AffineSolver s_flow("s_flow", part, "displacement", "pressure", two, Eigen::Vector2d(1.0, 0.0));
  AffineSolver s_structure("s_structure", part, "pressure", "displacement",
                           Eigen::Vector2d(-0.75, -0.25).asDiagonal().toDenseMatrix(),
                           Eigen::Vector2d::Zero());
  test_solvers()["s_flow"] = &s_flow;
  test_solvers()["s_structure"] = &s_structure;
  auto coupled = make_iqnism();
  coupled->initialize(flow, structure);
  coupled->solve_step(1, 0.1);
  ASSERT_GE(flow.inputs.size(), 2u);
  const double r1 = -0.75;  // x~_1 - x_1 on the second point, from x_1 = 0
  EXPECT_DOUBLE_EQ(flow.inputs[0](1), 0.0);
  EXPECT_NEAR(flow.inputs[1](1), 0.05 * r1, 1e-12);
}
