// Coupled solvers on an affine coupled problem with a known solution.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "coupler/coupled_solvers/coupled_solver.hpp"
#include "solver_wrappers/solver_error.hpp"
#include "tests/support/error_message.hpp"
#include "tests/support/linear_solvers.hpp"

using namespace cocopp;
using cocopp::testing::AffineSolver;

namespace {

/// Flow y = A x + b and structure x = B y with B A = `coupling` (a symmetric matrix of chosen
/// eigenvalues) so that Gauss-Seidel converges iff all |eigenvalues| < 1.
struct Problem {
  /// `load_scale`: the loads' size against the displacement's (the fixed point's displacement
  /// does not change with it).
  Problem(int n, double low, double high, double load_scale = 1.0)
      : part(cocopp::testing::line_model_part(n)) {
    const Eigen::MatrixXd q = Eigen::MatrixXd::Random(n, n).householderQr().householderQ();
    const Eigen::VectorXd eigenvalues = Eigen::VectorXd::LinSpaced(n, low, high);
    const Eigen::MatrixXd coupling = q * eigenvalues.asDiagonal() * q.transpose();
    const Eigen::MatrixXd a = Eigen::MatrixXd::Identity(n, n) * 2.0 * load_scale;
    const Eigen::MatrixXd b = coupling / (2.0 * load_scale);
    const Eigen::VectorXd offset = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0) * load_scale;
    flow = std::make_unique<AffineSolver>("flow", part, "displacement", "pressure", a, offset);
    structure = std::make_unique<AffineSolver>("structure", part, "pressure", "displacement", b,
                                               Eigen::VectorXd::Zero(n));
    solution = (Eigen::MatrixXd::Identity(n, n) - coupling).lu().solve(b * offset);  // B A = C
  }
  std::shared_ptr<const ModelPart> part;
  std::unique_ptr<AffineSolver> flow, structure;
  Eigen::VectorXd solution;  ///< radial displacement at the fixed point
};

std::unique_ptr<CoupledSolver> make(const std::string& type_and_settings, int max_iterations = 100,
                                    double load_tolerance = 1e-10) {
  // Side by side the loads' residual is measured too (absolute, `load_tolerance`).
  const bool parallel = type_and_settings.find("scheme: parallel") != std::string::npos;
  const std::string yaml =
      type_and_settings +
      (parallel ? fmt::format("\nload_criterion: {{type: absolute_norm, tolerance: {:g}}}",
                              load_tolerance)
                : "") +
      "\npredictor: {type: constant}\n"
      "convergence_criterion:\n  type: or\n  criteria:\n"
      "    - {type: absolute_norm, tolerance: 1e-10}\n"
      "    - {type: iteration_limit, maximum: " +
      std::to_string(max_iterations) + "}\n";
  return CoupledSolverRegistry::instance().create(Settings::load_string(yaml, "case.yaml"));
}

/// Run one step and return its record; the radial displacement must equal the solution.
StepRecord solve_one_step(CoupledSolver& coupled, Problem& problem) {
  coupled.initialize(*problem.flow, *problem.structure);
  StepRecord record = coupled.solve_step(1, 0.1);
  const auto x = coupled.x().values("wall", "displacement");
  EXPECT_LT((x.col(1) - problem.solution).norm(), 1e-8 * problem.solution.norm());
  EXPECT_TRUE(record.converged);
  return record;
}

}  // namespace

TEST(CoupledSolvers, GaussSeidelConvergesOnAContraction) {
  Problem problem(6, -0.5, 0.5);
  auto coupled = make("type: gauss_seidel");
  const StepRecord record = solve_one_step(*coupled, problem);
  EXPECT_GT(record.iterations, 10);
  EXPECT_EQ(record.residual_norms.size(), std::size_t(record.iterations));
}

TEST(CoupledSolvers, RelaxationAndAitkenConvergeWhereGaussSeidelDiverges) {
  Problem problem(6, -3.0, -1.5);
  solve_one_step(*make("type: relaxation\nomega: 0.3"), problem);
  Problem again(6, -3.0, -1.5);
  solve_one_step(*make("type: aitken\nomega_max: 0.3"), again);
}

// Aitken's residuals over two steps against the method written out as published (Kuttler and
// Wall 2008, eqs. 43-44, with the reference implementation's handling of steps): in a step,
// r_0 = G(x_0) - x_0 with G(x) = B (A x + b) and the factor carried over from the previous step,
// capped at omega_max (omega_max itself in the first step); then x_(k+1) = x_k + omega_k r_k and
// omega_(k+1) = -omega_k r_k . (r_(k+1) - r_k) / |r_(k+1) - r_k|^2, also for the residual that
// ends the step. The second step starts from the first's solution (constant predictor) with a
// changed offset, so its residuals depend on the factor carried over.
TEST(CoupledSolvers, AitkenFollowsThePublishedMethodAcrossSteps) {
  const int n = 6;
  const double omega_max = 1.0;  // above the factors of this problem (~0.3): no cap hides them
  auto published = [&](Problem& problem, int steps) {
    std::vector<std::vector<double>> norms(steps);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    double omega = omega_max;
    const auto output = [](const Interface& interface) {
      return Eigen::VectorXd(interface.values("wall", interface.blocks().front().variable).col(1));
    };
    auto g = [&](const Eigen::VectorXd& input) -> Eigen::VectorXd {
      Interface in = problem.flow->input_interface();
      in.values("wall", "displacement").col(1) = input;
      const Interface y = problem.flow->solve(in);
      return output(problem.structure->solve(y));
    };
    for (int step = 1; step <= steps; ++step) {
      problem.flow->initialize_step(step, 0.1 * step);
      problem.structure->initialize_step(step, 0.1 * step);
      Eigen::VectorXd r = g(x) - x;
      omega = std::copysign(std::min(std::abs(omega), omega_max), omega);
      norms[step - 1].push_back(r.norm());
      while (r.norm() > 1e-10 && norms[step - 1].size() < 100) {
        x += omega * r;
        const Eigen::VectorXd next = g(x) - x;
        omega = -omega * r.dot(next - r) / (next - r).squaredNorm();
        r = next;
        norms[step - 1].push_back(r.norm());
      }
    }
    return norms;
  };
  Problem problem(n, -3.0, -1.5);
  problem.flow->offset_variation = 0.3;
  // The coupled solver first: it starts from the structure's initial output, x = 0.
  auto coupled = make("type: aitken\nomega_max: 1.0");
  coupled->initialize(*problem.flow, *problem.structure);
  std::vector<StepRecord> records;
  for (int step = 1; step <= 2; ++step) records.push_back(coupled->solve_step(step, 0.1 * step));
  const auto expected = published(problem, 2);
  for (int step = 1; step <= 2; ++step) {
    const StepRecord& record = records[step - 1];
    const auto& reference = expected[step - 1];
    ASSERT_EQ(record.residual_norms.size(), reference.size())
        << "step " << step << ": " << ::testing::PrintToString(record.residual_norms) << " against "
        << ::testing::PrintToString(reference);
    for (std::size_t k = 0; k < reference.size(); ++k)
      EXPECT_NEAR(record.residual_norms[k], reference[k], 1e-9 * reference.front())
          << "step " << step << ", iteration " << k + 1;
  }
}

TEST(CoupledSolvers, GaussSeidelDivergenceIsDetectedWithAdvice) {
  Problem problem(6, -3.0, -1.5);
  auto coupled = make("type: gauss_seidel");
  coupled->initialize(*problem.flow, *problem.structure);
  try {
    coupled->solve_step(1, 0.1);
    FAIL() << "no divergence reported";
  } catch (const DivergenceError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("diverged in time step 1"), std::string::npos) << message;
    EXPECT_NE(message.find("iqni"), std::string::npos) << message;
  }
}

TEST(CoupledSolvers, IqnIlsSolvesALinearProblemInAtMostNPlusTwoIterations) {
  const int n = 8;
  Problem problem(n, -80.0, -1.2);  // strongly unstable for Gauss-Seidel
  auto coupled = make("type: iqni\nomega: 0.01\nmodel: {type: ls}");
  const StepRecord record = solve_one_step(*coupled, problem);
  // n secant columns (from n + 1 evaluations) span the space; the next evaluation converges.
  EXPECT_LE(record.iterations, n + 2);
}

// The solvers side by side (scheme parallel): the unknown is the radial displacement and the
// pressure stacked, 2n values that matter, and the map (x, y) -> (S(y), F(x)) is affine, so
// IQN-ILS spans it after 2n + 1 evaluations, with the residual-sum weights changing every
// iteration of the first step (the columns re-expressed in them exactly). Its fixed point is
// the serial one.
TEST(CoupledSolvers, SideBySideIqnIlsSolvesALinearProblemInAtMostTwiceNPlusTwoIterations) {
  const int n = 8;
  Problem problem(n, -80.0, -1.2);
  auto coupled = make("type: iqni\nscheme: parallel\nomega: 0.01\nmodel: {type: ls}");
  const StepRecord record = solve_one_step(*coupled, problem);
  // 2n + 2 evaluations span it; the last of them lands at 1.3e-10 here, the round-off of a
  // residual amplified 100-fold on the way, just above the 1e-10 threshold: one more.
  EXPECT_LE(record.iterations, 2 * n + 3);
  EXPECT_NE(coupled->describe().find("side by side"), std::string::npos) << coupled->describe();
}

// The loads a million times the displacement (their tolerance too): the residual-sum weights
// give each its say, and the iterations are those of the problem of equal sizes.
TEST(CoupledSolvers, SideBySideWeighsLoadsAgainstDisplacement) {
  const int n = 8;
  Problem problem(n, -80.0, -1.2, 1e6);
  auto coupled = make("type: iqni\nscheme: parallel\nomega: 0.01\nmodel: {type: ls}", 100, 1e-4);
  const StepRecord record = solve_one_step(*coupled, problem);
  EXPECT_LE(record.iterations, 2 * n + 3);
}

// IQN-MVJ side by side: its Jacobian carried in the residual-sum weights, re-expressed as they
// move (mv exactly; mvmf's kept columns refactorized), two steps of an affine problem whose
// solution moves: the second step starts from the first's Jacobian and needs fewer iterations.
TEST(CoupledSolvers, SideBySideMultiVectorCarriesItsJacobianAcrossSteps) {
  for (const char* model : {"mv", "mvmf"}) {
    const int n = 8;
    Problem problem(n, -80.0, -1.2);
    auto coupled = make(std::string("type: iqni\nscheme: parallel\nomega: 0.01\nmodel: {type: ") +
                        model + "}");
    const StepRecord first = solve_one_step(*coupled, problem);
    problem.flow->offset_variation = 0.5;  // the second step's solution elsewhere
    const StepRecord second = coupled->solve_step(2, 0.2);
    EXPECT_TRUE(second.converged) << model;
    EXPECT_LT(second.iterations, first.iterations) << model;
  }
}

TEST(CoupledSolvers, SideBySideAitkenConverges) {
  Problem problem(8, -0.9, 0.5);
  auto coupled = make("type: aitken\nscheme: parallel\nomega_max: 0.5");
  solve_one_step(*coupled, problem);
}

TEST(CoupledSolvers, SchemesAreChosenByNameAndSerialOnlyTypesSaySo) {
  std::string message = cocopp::testing::error_message<CaseError>(
      [] { make("type: iqni\nscheme: paralel\nmodel: {type: ls}"); });
  EXPECT_NE(message.find("did you mean 'parallel'"), std::string::npos) << message;
  message = cocopp::testing::error_message<CaseError>(
      [] { make("type: ibqn\nscheme: parallel\nmodel_f: {type: ls}\nmodel_s: {type: ls}"); });
  EXPECT_NE(message.find("cannot run the solvers side by side"), std::string::npos) << message;
  message = cocopp::testing::error_message<CaseError>([] {
    make("type: iqni\nload_criterion: {type: relative_norm, tolerance: 1e-6}\nmodel: {type: ls}");
  });
  EXPECT_NE(message.find("only the parallel scheme"), std::string::npos) << message;
  message = cocopp::testing::error_message<CaseError>([] {
    CoupledSolverRegistry::instance().create(Settings::load_string(
        "type: relaxation\nscheme: parallel\nomega: 0.5\npredictor: {type: constant}\n"
        "convergence_criterion: {type: absolute_norm, tolerance: 1e-10}\n",
        "case.yaml"));
  });
  EXPECT_NE(message.find("needs a load_criterion"), std::string::npos) << message;
}

// Anderson's mixing: the unexplained part of the residual relaxed by beta. The secant columns
// still span the space after n + 1 evaluations, so the linear problem converges as fast; but
// where Gauss-Seidel amplifies errors 80 times, IQN-ILS's residual grows 9-fold in the first
// iterations and mixing's do not (with and without variable scaling, which mixing undoes).
TEST(CoupledSolvers, MixingKeepsTheIteratesCloseAndSolvesALinearProblemAsFast) {
  const int n = 8;
  auto largest_growth = [](const StepRecord& record) {
    const auto& norms = record.residual_norms;
    return *std::max_element(norms.begin(), norms.end()) / norms.front();
  };
  Problem plain(n, -80.0, -1.2);
  const StepRecord iqn_ils =
      solve_one_step(*make("type: iqni\nomega: 0.01\nmodel: {type: ls}"), plain);
  for (const std::string scaling : {"", "\nscaling: {displacement: 1e3}"}) {
    Problem problem(n, -80.0, -1.2);
    const StepRecord mixed = solve_one_step(
        *make("type: iqni\nomega: 0.01\nmixing: 0.0125\nmodel: {type: ls}" + scaling), problem);
    EXPECT_LE(mixed.iterations, n + 2) << scaling;
    EXPECT_GT(largest_growth(iqn_ils), 5.0);  // measured: 9
    EXPECT_LT(largest_growth(mixed), 2.0) << scaling;
  }
}

TEST(CoupledSolvers, MixingNeedsALeastSquaresModel) {
  const std::string message = cocopp::testing::error_message<CaseError>(
      [] { make("type: iqni\nmixing: 0.5\nmodel: {type: mv}"); });
  EXPECT_NE(message.find("mixing"), std::string::npos) << message;
  EXPECT_NE(message.find("model 'ls' only"), std::string::npos) << message;
}

TEST(CoupledSolvers, ExplicitMakesOnePassPerStep) {
  Problem problem(4, -0.5, 0.5);
  auto coupled = make("type: explicit");
  coupled->initialize(*problem.flow, *problem.structure);
  const StepRecord record = coupled->solve_step(1, 0.1);
  EXPECT_EQ(record.iterations, 1);
  EXPECT_EQ(problem.flow->calls, 1);
  EXPECT_EQ(problem.structure->calls, 1);
}

TEST(CoupledSolvers, NonFiniteSolverOutputNamesTheSolver) {
  Problem problem(4, -0.5, 0.5);
  problem.flow->poison_at_call = 2;
  auto coupled = make("type: aitken");
  coupled->initialize(*problem.flow, *problem.structure);
  try {
    coupled->solve_step(3, 0.3);
    FAIL() << "no error for NaN";
  } catch (const DivergenceError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("solver 'flow' returned a non-finite pressure at model part 'wall', "
                           "point 0"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("time step 3, coupling iteration 2"), std::string::npos) << message;
  }
}

// Issue 51: the advice follows the method the run uses; a quasi-Newton run is not told to
// use one.
TEST(CoupledSolvers, DivergenceAdviceFollowsTheMethod) {
  const auto advice = [](const std::string& type) {
    Problem problem(4, -0.5, 0.5);
    problem.flow->poison_at_call = 2;
    auto coupled = make(type);
    coupled->initialize(*problem.flow, *problem.structure);
    try {
      coupled->solve_step(1, 0.1);
    } catch (const DivergenceError& e) {
      return std::string(e.what());
    }
    return std::string("no divergence reported");
  };
  const std::string iqni = advice("type: iqni\nomega: 0.05\nmodel: {type: ls, q: 10}");
  EXPECT_EQ(iqni.find("try coupled_solver type 'iqni'"), std::string::npos) << iqni;
  EXPECT_NE(iqni.find("relax the first update more (omega 0.05; try 0.005)"), std::string::npos)
      << iqni;
  const std::string aitken = advice("type: aitken\nomega_max: 0.5");
  EXPECT_NE(aitken.find("cap it lower (omega_max 0.5; try 0.05)"), std::string::npos) << aitken;
  const std::string relaxation = advice("type: relaxation\nomega: 0.5");
  EXPECT_NE(relaxation.find("need a quasi-Newton method: try coupled_solver type 'iqni'"),
            std::string::npos)
      << relaxation;
}

TEST(CoupledSolvers, MismatchedInterfacesAreReported) {
  auto part = cocopp::testing::line_model_part(3);
  auto other = cocopp::testing::line_model_part(4);
  AffineSolver flow("flow", part, "displacement", "pressure", Eigen::MatrixXd::Identity(3, 3),
                    Eigen::VectorXd::Zero(3));
  AffineSolver structure("structure", other, "pressure", "displacement",
                         Eigen::MatrixXd::Identity(4, 4), Eigen::VectorXd::Zero(4));
  auto coupled = make("type: gauss_seidel");
  try {
    coupled->initialize(flow, structure);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("do not fit together"), std::string::npos) << e.what();
  }
}

TEST(CoupledSolvers, TimingsAddUp) {
  Problem problem(4, -0.5, 0.5);
  auto coupled = make("type: gauss_seidel");
  coupled->initialize(*problem.flow, *problem.structure);
  const StepRecord record = coupled->solve_step(1, 0.1);
  ASSERT_EQ(record.solver_times.size(), 2u);
  EXPECT_NEAR(record.wall_time,
              record.solver_times[0] + record.solver_times[1] + record.coupler_time, 1e-12);
  EXPECT_GE(record.coupler_time, 0.0);
}

TEST(CoupledSolvers, SteadyResidualGrowthIsDetected) {
  // Relaxation with omega 0.9 on eigenvalues -1.5 .. -1.4 multiplies the error by about -1.2
  // per iteration: far from the growth factor within the iteration limit, but persistent.
  Problem problem(4, -1.5, -1.4);
  const std::string yaml =
      "type: relaxation\nomega: 0.9\ndivergence: {factor: 1e12, growth_iterations: 10}\n"
      "predictor: {type: constant}\n"
      "convergence_criterion: {type: iteration_limit, maximum: 100}\n";
  auto coupled = CoupledSolverRegistry::instance().create(Settings::load_string(yaml, "case.yaml"));
  coupled->initialize(*problem.flow, *problem.structure);
  try {
    coupled->solve_step(1, 0.1);
    FAIL() << "no divergence reported";
  } catch (const DivergenceError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("grew in each of the last 10 iterations, more than doubling"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("in iteration 11"), std::string::npos) << message;
  }
}

namespace {

/// A flow that rejects displacements longer than `limit` (as a mesh that would turn inside
/// out), keeping the inputs it was given.
class RejectingFlow : public AffineSolver {
 public:
  using AffineSolver::AffineSolver;
  const Interface& solve(const Interface& input) override {
    const Eigen::VectorXd x = input.values("wall", "displacement").col(1);
    inputs.push_back(x);
    if (x.norm() > limit) {
      std::this_thread::sleep_for(std::chrono::milliseconds(rejection_milliseconds));
      throw SolverRejectedInput(name(), "the displacement is too large");
    }
    return AffineSolver::solve(input);
  }
  double limit = 0.0;
  int rejection_milliseconds = 0;  ///< what a rejection costs, as ccx's cutbacks do
  std::vector<Eigen::VectorXd> inputs;
};

/// Relaxation with omega 1.3 on B A with eigenvalues in [-0.3, 0.1]: the first relaxed step
/// x1 = 1.3 B b is longer than the solution x* = (I - B A)^-1 B b (1.3 > 1 / (1 - lambda)), so
/// a flow that rejects displacements longer than (|x*| + |x1|) / 2 rejects it.
struct RejectingProblem : Problem {
  RejectingProblem() : Problem(6, -0.3, 0.1) {
    const Eigen::VectorXd offset = Eigen::VectorXd::LinSpaced(6, 1.0, 2.0);
    flow = std::make_unique<RejectingFlow>("flow", part, "displacement", "pressure",
                                           2.0 * Eigen::MatrixXd::Identity(6, 6), offset);
    first_step = 1.3 * structure_matrix() * offset;
  }
  Eigen::MatrixXd structure_matrix() const {
    Eigen::MatrixXd b(6, 6);
    for (int j = 0; j < 6; ++j) {
      Interface in({{part, {"pressure"}}});
      in.values("wall", "pressure").setZero();
      in.values("wall", "pressure")(j, 0) = 1.0;
      b.col(j) = structure->solve(in).values("wall", "displacement").col(1);
      in.values("wall", "pressure").setZero();
      structure->solve(in);  // the initial state again: x = 0
    }
    structure->calls = 0;
    return b;
  }
  RejectingFlow& rejecting() { return static_cast<RejectingFlow&>(*flow); }
  Eigen::VectorXd first_step;
};

}  // namespace

TEST(CoupledSolvers, RejectedInputIsRetriedHalfwayFromTheLastAcceptedOne) {
  RejectingProblem problem;
  ASSERT_GT(problem.first_step.norm(), problem.solution.norm());
  problem.rejecting().limit = 0.5 * (problem.first_step.norm() + problem.solution.norm());
  auto coupled = make("type: relaxation\nomega: 1.3", 200);
  const StepRecord record = solve_one_step(*coupled, problem);
  const auto& inputs = problem.rejecting().inputs;
  ASSERT_GE(inputs.size(), 3u);
  EXPECT_EQ(inputs[0].norm(), 0.0);  // the initial state, accepted
  EXPECT_LT((inputs[1] - problem.first_step).norm(), 1e-14);
  EXPECT_LT((inputs[2] - 0.5 * problem.first_step).norm(), 1e-14);
  ASSERT_FALSE(record.warnings.empty());
  EXPECT_EQ(record.warnings.front().rfind("solver 'flow' rejected the input of iteration 2: the "
                                          "step from the last accepted input was shortened 1 "
                                          "time(s) by 0.5",
                                          0),
            0u)
      << record.warnings.front();
  // A rejected input is no iteration: one residual per accepted input.
  EXPECT_EQ(record.residual_norms.size(), std::size_t(record.iterations));
  EXPECT_GT(int(inputs.size()), record.iterations);
}

TEST(CoupledSolvers, TheTimeOfARejectedSolveIsTheSolvers) {
  RejectingProblem problem;
  problem.rejecting().limit = 0.5 * (problem.first_step.norm() + problem.solution.norm());
  problem.rejecting().rejection_milliseconds = 200;
  auto coupled = make("type: relaxation\nomega: 1.3", 200);
  const StepRecord record = solve_one_step(*coupled, problem);
  EXPECT_GE(record.solver_times[0], 0.2);
  EXPECT_LT(record.coupler_time, 0.1);
}

TEST(CoupledSolvers, RejectionsBeyondTheRetriesStopTheRunNamingTheSetting) {
  RejectingProblem problem;
  problem.rejecting().limit = 1e-3 * problem.first_step.norm();
  auto coupled = make("type: relaxation\nomega: 1.3\nbacktracking: {retries: 3, factor: 0.5}");
  coupled->initialize(*problem.flow, *problem.structure);
  const std::string message =
      cocopp::testing::error_message<SolverError>([&] { coupled->solve_step(1, 0.1); });
  EXPECT_NE(message.find("the displacement is too large"), std::string::npos) << message;
  EXPECT_NE(message.find("stepped back 3 times"), std::string::npos) << message;
  EXPECT_NE(message.find("coupled_solver.backtracking.retries = 3"), std::string::npos) << message;
  EXPECT_EQ(problem.rejecting().inputs.size(), 5u);  // accepted, rejected, 3 retries
}
