// The multi-vector models `mv` (dense) and `mvmf` (matrix-free), alone and inside iqni, next to
// `ls`, on affine coupled problems with known solutions.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <sstream>

#include "coupler/coupled_solvers/coupled_solver.hpp"
#include "coupler/coupled_solvers/models/model.hpp"
#include "tests/support/linear_solvers.hpp"

using namespace cocopp;
using cocopp::testing::AffineSolver;

namespace {

std::unique_ptr<Model> make_model(const std::string& yaml) {
  return ModelRegistry::instance().create(Settings::load_string(yaml, "model.yaml"));
}

/// An affine solver whose offset grows by `drift` every time step, so that the fixed point of
/// the coupled problem moves from step to step while its Jacobian stays the same.
class DriftingSolver : public SolverWrapper {
 public:
  DriftingSolver(std::unique_ptr<AffineSolver> inner, Eigen::VectorXd drift)
      : inner_(std::move(inner)), drift_(std::move(drift)) {}

  const std::string& name() const override { return inner_->name(); }
  void initialize() override {
    inner_->initialize();
    output_ = inner_->output_interface();
  }
  const Interface& input_interface() const override { return inner_->input_interface(); }
  const Interface& output_interface() const override { return output_; }
  void initialize_step(int step, double time) override {
    step_ = step;
    inner_->initialize_step(step, time);
  }
  const Interface& solve(const Interface& input) override {
    output_ = inner_->solve(input);
    const auto& block = output_.blocks().front();
    auto out = output_.values(block.model_part, block.variable);
    out.col(out.cols() > 1 ? 1 : 0) += step_ * drift_;
    return output_;
  }
  void finalize_step() override { inner_->finalize_step(); }
  void output_step() override { inner_->output_step(); }
  void finalize() override { inner_->finalize(); }

 private:
  std::unique_ptr<AffineSolver> inner_;
  Eigen::VectorXd drift_;
  Interface output_;
  int step_ = 0;
};

/// Flow y = A x + b + step d and structure x = B y with B A = `coupling`, a symmetric matrix
/// with eigenvalues evenly spaced in [low, high] (as in test_coupled_solvers.cpp). Below -1,
/// Gauss-Seidel diverges. n unknowns: the radial displacement of n points.
struct Problem {
  Problem(int n, double low, double high, unsigned seed = 1)
      : part(cocopp::testing::line_model_part(n)) {
    std::srand(seed);
    const Eigen::MatrixXd q = Eigen::MatrixXd::Random(n, n).householderQr().householderQ();
    const Eigen::VectorXd eigenvalues = Eigen::VectorXd::LinSpaced(n, low, high);
    coupling = q * eigenvalues.asDiagonal() * q.transpose();
    const Eigen::MatrixXd a = Eigen::MatrixXd::Identity(n, n) * 2.0;
    b = coupling / 2.0;
    offset = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
    drift = Eigen::VectorXd::Random(n);
    flow = std::make_unique<DriftingSolver>(
        std::make_unique<AffineSolver>("flow", part, "displacement", "pressure", a, offset), drift);
    structure = std::make_unique<AffineSolver>("structure", part, "pressure", "displacement", b,
                                               Eigen::VectorXd::Zero(n));
  }
  /// The radial displacement at the fixed point of time step `step`.
  Eigen::VectorXd solution(int step) const {
    const Eigen::Index n = offset.size();
    return (Eigen::MatrixXd::Identity(n, n) - coupling).lu().solve(b * (offset + step * drift));
  }

  std::shared_ptr<const ModelPart> part;
  Eigen::MatrixXd coupling, b;
  Eigen::VectorXd offset, drift;
  std::unique_ptr<DriftingSolver> flow;
  std::unique_ptr<AffineSolver> structure;
};

std::unique_ptr<CoupledSolver> make_iqni(const std::string& model, double tolerance) {
  std::ostringstream yaml;
  yaml << "type: iqni\nomega: 0.01\nmodel: " << model
       << "\npredictor: {type: constant}\n"
          "convergence_criterion:\n  type: or\n  criteria:\n"
          "    - {type: absolute_norm, tolerance: "
       << tolerance << "}\n    - {type: iteration_limit, maximum: 100}\n";
  return CoupledSolverRegistry::instance().create(Settings::load_string(yaml.str(), "case.yaml"));
}

/// Solve `steps` time steps; returns the iterations (solver evaluations) of each step and
/// checks every step's solution.
std::vector<int> iterations_per_step(const std::string& model, Problem& problem, int steps,
                                     double tolerance = 1e-10) {
  auto coupled = make_iqni(model, tolerance);
  coupled->initialize(*problem.flow, *problem.structure);
  std::vector<int> iterations;
  for (int step = 1; step <= steps; ++step) {
    const StepRecord record = coupled->solve_step(step, 0.1 * step);
    EXPECT_TRUE(record.converged) << model << " step " << step;
    const auto x = coupled->x().values("wall", "displacement");
    const Eigen::VectorXd expected = problem.solution(step);
    EXPECT_LT((x.col(1) - expected).norm(), 1e-8 * expected.norm()) << model << " step " << step;
    iterations.push_back(record.iterations);
  }
  return iterations;
}

Eigen::VectorXd vec(std::initializer_list<double> values) {
  Eigen::VectorXd v(values.size());
  int i = 0;
  for (double x : values) v(i++) = x;
  return v;
}

}  // namespace

class EveryModel : public ::testing::TestWithParam<const char*> {};

// Iterations count solver evaluations (F then S) in the step, the first one included. The
// first evaluation's residual is relaxed; each later one adds a secant column. After
// n + 1 evaluations the n columns span the space, the secant prediction is exact, and the
// next evaluation confirms it: at most n + 2 evaluations, i.e. n + 1 quasi-Newton updates.
TEST_P(EveryModel, SolvesAnAffineProblemInAtMostNPlusOneUpdates) {
  const int n = 8;
  Problem problem(n, -80.0, -1.2);  // Gauss-Seidel diverges: eigenvalues well below -1
  const std::string model = std::string("{type: ") + GetParam() + "}";
  const std::vector<int> iterations = iterations_per_step(model, problem, 1);
  EXPECT_LE(iterations[0], n + 2);
  EXPECT_GE(iterations[0], n);  // n - 1 columns cannot explain a generic n-dimensional problem
}

INSTANTIATE_TEST_SUITE_P(MultiVector, EveryModel, ::testing::Values("ls", "mv", "mvmf"));

// The carried Jacobian: after a first step that collects n columns, J is exact for a linear
// problem, and every later step needs one evaluation at the predicted x and one at x~ - J r.
// The residual of that second evaluation is round-off (about 1e-12 of the first): the
// tolerance stays well above it, so that mv and mvmf make the same number of iterations.
TEST(MultiVector, CarriedJacobianSpeedsUpLaterSteps) {
  const int n = 8;
  const double tolerance = 1e-8;  // the first residual of a step is about 30
  Problem problem(n, -80.0, -1.2);
  const std::vector<int> mv = iterations_per_step("{type: mv}", problem, 5, tolerance);
  for (std::size_t step = 1; step < mv.size(); ++step) {
    EXPECT_LT(mv[step], mv[0]) << "step " << step + 1;
    EXPECT_LE(mv[step], 2) << "step " << step + 1;
  }
  Problem again(n, -80.0, -1.2);
  EXPECT_EQ(iterations_per_step("{type: mvmf, q: 100}", again, 5, tolerance), mv);
}

// mvmf with q = 0 keeps nothing across steps: it is IQN-ILS without reuse.
TEST(MultiVector, MatrixFreeWithoutReuseIsLeastSquares) {
  const int n = 6;
  Problem problem(n, -20.0, -1.5);
  const std::vector<int> ls = iterations_per_step("{type: ls}", problem, 3);
  Problem again(n, -20.0, -1.5);
  EXPECT_EQ(iterations_per_step("{type: mvmf, q: 0}", again, 3), ls);
}

// mv and mvmf (q covering all steps) on the same sequence of add() calls: the same predictions
// to round-off. Steps are cut short (4 evaluations, 3 columns of 10), so J_prev is built from
// several steps and the recursion of mvmf goes several levels deep.
TEST(MultiVector, DenseAndMatrixFreeGiveTheSamePredictions) {
  const int n = 10;
  std::srand(7);
  const Eigen::MatrixXd q = Eigen::MatrixXd::Random(n, n).householderQr().householderQ();
  const Eigen::MatrixXd coupling =
      q * Eigen::VectorXd::LinSpaced(n, -30.0, -1.5).asDiagonal() * q.transpose();
  auto mv = make_model("type: mv");
  auto mvmf = make_model("type: mvmf\nq: 100");
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  int compared = 0;
  for (int step = 0; step < 6; ++step) {
    const Eigen::VectorXd offset = Eigen::VectorXd::Random(n);
    mv->initialize_step();
    mvmf->initialize_step();
    for (int iteration = 0; iteration < 4; ++iteration) {
      const Eigen::VectorXd xt = coupling * x + offset;
      const Eigen::VectorXd r = xt - x;
      mv->add(r, xt);
      mvmf->add(r, xt);
      ASSERT_EQ(mv->is_ready(), mvmf->is_ready());
      ASSERT_EQ(mv->columns(), mvmf->columns());
      if (!mv->is_ready()) {
        x += 0.01 * r;
        continue;
      }
      const Eigen::VectorXd dr = Eigen::VectorXd::Random(n);
      EXPECT_TRUE(mvmf->predict(dr).isApprox(mv->predict(dr), 1e-10)) << step << " " << iteration;
      const Eigen::VectorXd dxt = mv->predict(-r);
      EXPECT_TRUE(mvmf->predict(-r).isApprox(dxt, 1e-10)) << step << " " << iteration;
      x = xt + dxt;
      ++compared;
    }
    mv->finalize_step();
    mvmf->finalize_step();
  }
  EXPECT_EQ(compared, 23);  // all but the very first iteration
}

// In its first step (J_prev = 0) mv is IQN-ILS, and the secant equations J V = W hold.
TEST(MultiVector, FirstStepIsLeastSquaresAndSatisfiesTheSecantEquations) {
  const int n = 5;
  std::srand(11);
  auto mv = make_model("type: mv");
  auto ls = make_model("type: ls");
  mv->initialize_step();
  ls->initialize_step();
  Eigen::VectorXd r_old, xt_old;
  for (int iteration = 0; iteration < 4; ++iteration) {
    const Eigen::VectorXd r = Eigen::VectorXd::Random(n), xt = Eigen::VectorXd::Random(n);
    mv->add(r, xt);
    ls->add(r, xt);
    if (iteration > 0) {
      EXPECT_TRUE(mv->predict(r - r_old).isApprox(xt - xt_old, 1e-12));
      const Eigen::VectorXd dr = Eigen::VectorXd::Random(n);
      EXPECT_TRUE(mv->predict(dr).isApprox(ls->predict(dr), 1e-12));
    }
    r_old = r;
    xt_old = xt;
  }
}

TEST(MultiVector, RepeatedOrZeroResidualGivesFiniteOutputs) {
  for (const char* type : {"mv", "mvmf"}) {
    auto model = make_model(std::string("type: ") + type);
    model->initialize_step();
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(3);
    model->add(zero, zero);
    model->add(zero, zero);  // zero residual twice: a zero column, dropped
    EXPECT_FALSE(model->is_ready()) << type;
    EXPECT_TRUE(model->predict(vec({1, 2, 3})).allFinite()) << type;
    const Eigen::VectorXd r = vec({1, 2, 3});
    model->add(r, r);
    model->add(r, r);  // repeated residual: a zero column, dropped
    EXPECT_EQ(model->columns(), 1) << type;
    model->finalize_step();
    model->initialize_step();
    model->add(r, r);
    model->add(r, r);
    EXPECT_EQ(model->columns(), 1) << type;  // the carried column only
    EXPECT_TRUE(model->predict(-r).allFinite()) << type;
  }
}

// More columns than unknowns in one step: the filter keeps at most n, the newest, and the
// newest secant equation holds.
TEST(MultiVector, MoreColumnsThanRowsAreFiltered) {
  for (const char* type : {"mv", "mvmf"}) {
    std::srand(5);
    auto model = make_model(std::string("type: ") + type);
    model->initialize_step();
    Eigen::VectorXd r_old, xt_old;
    for (int iteration = 0; iteration < 8; ++iteration) {
      const Eigen::VectorXd r = Eigen::VectorXd::Random(3), xt = Eigen::VectorXd::Random(3);
      model->add(r, xt);
      EXPECT_LE(model->columns(), 3) << type;
      if (iteration > 0) {
        EXPECT_TRUE(model->predict(r - r_old).isApprox(xt - xt_old, 1e-10)) << type;
      }
      r_old = r;
      xt_old = xt;
    }
    bool warned = false;
    for (const auto& note : model->take_notes())
      warned = warned || note.find("more columns than unknowns") != std::string::npos;
    EXPECT_TRUE(warned) << type;
    model->finalize_step();
    EXPECT_TRUE(model->predict(vec({1, -1, 2})).allFinite()) << type;
  }
}

// A step converging in its first iteration adds no columns and leaves J_prev as it was.
TEST(MultiVector, StepWithoutColumnsKeepsTheCarriedJacobian) {
  for (const char* type : {"mv", "mvmf"}) {
    std::srand(9);
    auto model = make_model(std::string("type: ") + type);
    model->initialize_step();
    for (int iteration = 0; iteration < 3; ++iteration)
      model->add(Eigen::VectorXd::Random(4), Eigen::VectorXd::Random(4));
    model->finalize_step();
    const Eigen::VectorXd dr = Eigen::VectorXd::Random(4);
    model->initialize_step();
    const Eigen::VectorXd before = model->predict(dr);
    model->add(Eigen::VectorXd::Random(4), Eigen::VectorXd::Random(4));
    model->finalize_step();  // converged at once
    model->initialize_step();
    EXPECT_TRUE(model->is_ready()) << type;
    EXPECT_EQ(model->columns(), 2) << type;
    EXPECT_TRUE(model->predict(dr).isApprox(before, 1e-14)) << type;
  }
}

// mvmf forgets steps older than q: with q = 1 only the last step with columns is kept.
TEST(MultiVector, MatrixFreeKeepsQSteps) {
  auto model = make_model("type: mvmf\nq: 1");
  auto add_step = [&](double scale) {
    model->initialize_step();
    model->add(vec({0, 0}), vec({0, 0}));
    model->add(vec({scale, 0}), vec({0, scale}));
    model->finalize_step();
  };
  add_step(1.0);
  add_step(2.0);
  model->initialize_step();
  EXPECT_EQ(model->columns(), 1);
}

TEST(MultiVector, InvalidSettings) {
  EXPECT_THROW(make_model("type: mvmf\nq: -1"), CaseError);
  EXPECT_THROW(make_model("type: mvmf\nmin_significant: -1"), CaseError);
  EXPECT_THROW(make_model("type: mv\nmin_significant: -1"), CaseError);
}
