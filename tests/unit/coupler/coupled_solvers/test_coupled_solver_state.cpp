// The coupled-solver state: a run split in two, the second half started from the state the
// first half saved (through the HDF5 state file), must repeat the uninterrupted run exactly:
// same iterations in every step, same interface values.
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Dense>
#include <filesystem>

#include "coupler/coupled_solvers/coupled_solver.hpp"
#include "coupler/results/state_file.hpp"
#include "tests/support/linear_solvers.hpp"

using namespace cocopp;
using cocopp::testing::AffineSolver;

namespace {

constexpr int kPoints = 6;

/// An affine flow-structure pair whose solution moves from step to step, with one unstable
/// Gauss-Seidel mode (relaxation-free methods must learn it and carry it across steps).
struct MovingProblem {
  MovingProblem() : part(cocopp::testing::line_model_part(kPoints)) {
    std::srand(5);
    const Eigen::MatrixXd q =
        Eigen::MatrixXd::Random(kPoints, kPoints).householderQr().householderQ();
    const Eigen::VectorXd eigenvalues = Eigen::VectorXd::LinSpaced(kPoints, -3.0, 0.4);
    const Eigen::MatrixXd coupling = q * eigenvalues.asDiagonal() * q.transpose();
    flow = std::make_unique<AffineSolver>("flow", part, "displacement", "pressure",
                                          Eigen::MatrixXd::Identity(kPoints, kPoints),
                                          Eigen::VectorXd::LinSpaced(kPoints, 1.0, 2.0));
    flow->offset_variation = 0.3;
    structure = std::make_unique<AffineSolver>("structure", part, "pressure", "displacement",
                                               coupling, Eigen::VectorXd::Zero(kPoints));
  }
  std::shared_ptr<const ModelPart> part;
  std::unique_ptr<AffineSolver> flow, structure;
};

std::unique_ptr<CoupledSolver> make(const std::string& settings) {
  return CoupledSolverRegistry::instance().create(Settings::load_string(
      settings +
          "\npredictor: {type: quadratic}\nconvergence_criterion: {type: or, criteria: "
          "[{type: relative_norm, tolerance: 1e-9}, {type: iteration_limit, maximum: 40}]}\n",
      "case.yaml"));
}

struct StepResult {
  int iterations;
  Eigen::VectorXd x;
};

std::vector<StepResult> run_steps(CoupledSolver& coupled, int first, int last) {
  std::vector<StepResult> results;
  for (int step = first; step <= last; ++step) {
    const StepRecord record = coupled.solve_step(step, 0.1 * step);
    results.push_back({record.iterations, coupled.x().data()});
  }
  return results;
}

class CoupledSolverState : public ::testing::TestWithParam<const char*> {};

}  // namespace

TEST_P(CoupledSolverState, ARunRestartedFromTheSavedStateRepeatsTheUninterruptedRun) {
  const int steps = 8, split = 4;
  MovingProblem whole_problem;
  auto whole = make(GetParam());
  whole->initialize(*whole_problem.flow, *whole_problem.structure);
  const auto expected = run_steps(*whole, 1, steps);

  // ctest runs the parameterised cases in parallel processes: one file each.
  const auto file = std::filesystem::temp_directory_path() /
                    ("cocopp_test_state_" + std::to_string(::getpid()) + ".h5");
  {
    MovingProblem problem;
    auto first_half = make(GetParam());
    first_half->initialize(*problem.flow, *problem.structure);
    run_steps(*first_half, 1, split);
    SavedState saved;
    saved.step = split;
    first_half->save_state(saved.state);
    // The split must fall where the models hold columns, or the test would prove little.
    for (const char* model : {"model", "model_f", "model_s"})
      if (saved.state.has_group(model)) {
        const State& group = saved.state.group(model);
        const double held = group.has("v")       ? double(group.matrix("v").cols())
                            : group.has("steps") ? group.scalar("steps")
                                                 : double(group.matrix("jacobian").size());
        EXPECT_GT(held, 0.0) << model;
      }
    write_state_file(file, saved);
  }
  MovingProblem problem;
  auto second_half = make(GetParam());
  second_half->initialize(*problem.flow, *problem.structure);
  const SavedState loaded = read_state_file(file);
  EXPECT_EQ(loaded.step, split);
  second_half->load_state(loaded.state);
  const auto continued = run_steps(*second_half, split + 1, steps);
  std::filesystem::remove(file);

  for (int i = 0; i < steps - split; ++i) {
    const StepResult& want = expected[std::size_t(split + i)];
    EXPECT_EQ(continued[std::size_t(i)].iterations, want.iterations) << "step " << split + 1 + i;
    EXPECT_LT((continued[std::size_t(i)].x - want.x).norm(), 1e-12 * want.x.norm())
        << "step " << split + 1 + i;
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllWithMemory, CoupledSolverState,
    ::testing::Values(
        "type: iqni\nomega: 0.1\nmodel: {type: ls, q: 3}",
        "type: iqni\nomega: 0.1\nmodel: {type: ls, q: 3}\nscaling: automatic",
        "type: iqni\nomega: 0.1\nmodel: {type: mv}",
        "type: iqni\nomega: 0.1\nmodel: {type: mvmf, q: 3}",
        "type: ibqn\nomega: 0.1\nmodel_f: {type: ls, q: 3}\nmodel_s: {type: ls, q: 3}",
        "type: aitken\nomega_max: 0.3"));

TEST(CoupledSolverState, ForeignStateIsRejectedWithTheMissingName) {
  MovingProblem problem;
  auto aitken = make("type: aitken");
  aitken->initialize(*problem.flow, *problem.structure);
  State state;
  aitken->save_state(state);
  MovingProblem other;
  auto iqni = make("type: iqni\nmodel: {type: ls}");
  iqni->initialize(*other.flow, *other.structure);
  try {
    iqni->load_state(state);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("'model'"), std::string::npos) << e.what();
  }
}
