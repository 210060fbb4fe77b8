// Convergence criteria and their combinations.
#include <gtest/gtest.h>

#include "coupler/convergence/convergence_criterion.hpp"
#include "tests/support/linear_solvers.hpp"

using namespace cocopp;

namespace {

std::unique_ptr<ConvergenceCriterion> make(const std::string& yaml) {
  return ConvergenceCriterionRegistry::instance().create(Settings::load_string(yaml, "c.yaml"));
}

Eigen::VectorXd residual(double norm) {
  return Eigen::VectorXd::Constant(4, norm / 2.0);
}

}  // namespace

TEST(Convergence, AbsoluteNorm) {
  auto c = make("type: absolute_norm\ntolerance: 1e-3");
  c->initialize_step();
  EXPECT_FALSE(c->is_satisfied());
  c->update(residual(2e-3));
  EXPECT_FALSE(c->is_satisfied());
  c->update(residual(0.5e-3));
  EXPECT_TRUE(c->is_satisfied());
  EXPECT_TRUE(c->tolerance_met());
}

TEST(Convergence, AbsoluteNormInfinityOrder) {
  auto c = make("type: absolute_norm\ntolerance: 0.6\norder: inf");
  c->initialize_step();
  c->update(residual(1.0));  // entries 0.5, 2-norm 1.0
  EXPECT_TRUE(c->is_satisfied());
}

TEST(Convergence, RelativeNormIsRelativeToTheFirstResidualOfTheStep) {
  auto c = make("type: relative_norm\ntolerance: 1e-2");
  c->initialize_step();
  c->update(residual(10.0));
  c->update(residual(0.2));
  EXPECT_FALSE(c->is_satisfied());
  c->update(residual(0.05));
  EXPECT_TRUE(c->is_satisfied());
  c->initialize_step();  // a new step resets the reference
  c->update(residual(0.05));
  EXPECT_FALSE(c->is_satisfied());
}

// Side by side (scheme parallel) the first displacement residual can be tiny while the next
// is not: `reference: largest` measures against the largest residual of the step so far.
TEST(Convergence, RelativeNormToTheLargestResidualOfTheStep) {
  auto c = make("type: relative_norm\ntolerance: 1e-2\nreference: largest");
  c->initialize_step();
  c->update(residual(1e-6));
  c->update(residual(10.0));
  c->update(residual(0.2));
  EXPECT_FALSE(c->is_satisfied());
  c->update(residual(0.05));
  EXPECT_TRUE(c->is_satisfied());
  EXPECT_NE(c->describe().find("to the largest"), std::string::npos) << c->describe();
  auto first = make("type: relative_norm\ntolerance: 1e-2");
  first->initialize_step();
  for (double norm : {1e-6, 10.0, 0.2, 0.05}) first->update(residual(norm));
  EXPECT_FALSE(first->is_satisfied());  // 0.05 against the first 1e-6
}

// A combination says whether it stopped at an iteration limit, so that a second criterion
// (the loads' side by side) cannot keep a step going past it.
TEST(Convergence, LimitReachedIsSeenThroughCombinations) {
  auto c = make(
      "type: or\ncriteria:\n  - {type: absolute_norm, tolerance: 1e-9}\n"
      "  - {type: iteration_limit, maximum: 2}");
  c->initialize_step();
  c->update(residual(1));
  EXPECT_FALSE(c->limit_reached());
  c->update(residual(1));
  EXPECT_TRUE(c->limit_reached());
  EXPECT_FALSE(make("type: absolute_norm\ntolerance: 1")->limit_reached());
}

// preCICE's relative measure: the residual against the output it belongs to, no history.
TEST(Convergence, ValueRelativeNormMeasuresTheResidualAgainstTheOutput) {
  auto c = make("type: value_relative_norm\ntolerance: 1e-3");
  c->initialize_step();
  c->set_output(residual(100.0));
  c->update(residual(0.2));
  EXPECT_FALSE(c->is_satisfied());
  c->set_output(residual(100.0));
  c->update(residual(0.05));
  EXPECT_TRUE(c->is_satisfied());
  EXPECT_TRUE(c->tolerances().empty());  // no fixed line for a plot of ||r||
  c->set_output(Eigen::VectorXd::Zero(4));
  c->update(residual(1e-30));
  EXPECT_FALSE(c->is_satisfied());  // any residual against a zero output
  c->update(Eigen::VectorXd::Zero(4));
  EXPECT_TRUE(c->is_satisfied());
  // Combinations hand the output on.
  auto combined = make(
      "type: or\ncriteria:\n  - {type: value_relative_norm, tolerance: 1e-3}\n"
      "  - {type: iteration_limit, maximum: 10}");
  combined->initialize_step();
  combined->set_output(residual(100.0));
  combined->update(residual(0.05));
  EXPECT_TRUE(combined->tolerance_met());
}

TEST(Convergence, RelativeNormWithZeroFirstResidualIsConverged) {
  auto c = make("type: relative_norm\ntolerance: 1e-6");
  c->initialize_step();
  c->update(Eigen::VectorXd::Zero(3));
  EXPECT_TRUE(c->is_satisfied());
}

TEST(Convergence, IterationLimitStopsWithoutMeetingATolerance) {
  auto c = make("type: iteration_limit\nmaximum: 2");
  c->initialize_step();
  c->update(residual(1));
  EXPECT_FALSE(c->is_satisfied());
  c->update(residual(1));
  EXPECT_TRUE(c->is_satisfied());
  EXPECT_FALSE(c->tolerance_met());
}

TEST(Convergence, OrAndNesting) {
  auto c = make(
      "type: or\ncriteria:\n  - {type: relative_norm, tolerance: 1e-6}\n"
      "  - {type: iteration_limit, maximum: 3}");
  c->initialize_step();
  for (int i = 0; i < 2; ++i) c->update(residual(1));
  EXPECT_FALSE(c->is_satisfied());
  c->update(residual(1));
  EXPECT_TRUE(c->is_satisfied());
  EXPECT_FALSE(c->tolerance_met());

  auto both = make(
      "type: and\ncriteria:\n  - {type: absolute_norm, tolerance: 1}\n"
      "  - {type: iteration_limit, maximum: 2}");  // at least two iterations
  both->initialize_step();
  both->update(residual(0.1));
  EXPECT_FALSE(both->is_satisfied());
  both->update(residual(0.1));
  EXPECT_TRUE(both->is_satisfied());
  EXPECT_TRUE(both->tolerance_met());
  EXPECT_EQ(both->describe(), "(absolute_norm(2) < 1 and iteration_limit 2)");
}

TEST(Convergence, EmptyCombinationIsAnError) {
  EXPECT_THROW(make("type: or\ncriteria: []"), CaseError);
}

namespace {

/// A solver whose answer to "converged at the first iteration" the test sets.
class ReportingSolver : public cocopp::testing::InProcessSolver {
 public:
  explicit ReportingSolver(std::string name, bool can_report = true)
      : InProcessSolver(std::move(name), Interface(), Interface()), can_report_(can_report) {}
  const Interface& solve(const Interface&) override { return output_; }
  void start_reporting_convergence() override {
    if (!can_report_) SolverWrapper::start_reporting_convergence();
    ++report_requests;
  }
  bool converged_at_first_iteration() const override { return converged; }
  bool converged = false;
  int report_requests = 0;

 private:
  bool can_report_;
};

}  // namespace

TEST(Convergence, SolverCouplingConvergenceFollowsTheNamedSolversReport) {
  auto c = make("type: solver_coupling_convergence\nsolver_index: 1");
  EXPECT_EQ(c->describe(), "solver_coupling_convergence(solver_index 1)");  // before the run
  ReportingSolver flow("flow"), wall("wall");
  c->attach_solvers({&flow, &wall});
  EXPECT_EQ(flow.report_requests, 0);  // only the solver it names is asked
  EXPECT_EQ(wall.report_requests, 1);
  EXPECT_EQ(c->describe(), "solver_coupling_convergence(wall)");
  c->initialize_step();
  EXPECT_FALSE(c->is_satisfied());
  flow.converged = true;  // the other solver's report does not count
  c->update(residual(1.0));
  EXPECT_FALSE(c->is_satisfied());
  EXPECT_EQ(c->progress(), "wall iterating");
  wall.converged = true;
  c->update(residual(1.0));
  EXPECT_TRUE(c->is_satisfied());
  EXPECT_TRUE(c->tolerance_met());
  EXPECT_EQ(c->progress(), "wall converged");
  c->initialize_step();  // a new step starts unconverged, whatever the last report said
  EXPECT_FALSE(c->is_satisfied());
}

TEST(Convergence, SolverCouplingConvergenceOfBothSolversInsideAnd) {
  auto c = make(
      "type: and\ncriteria:\n  - {type: solver_coupling_convergence, solver_index: 0}\n"
      "  - {type: solver_coupling_convergence, solver_index: 1}");
  ReportingSolver flow("flow"), wall("wall");
  c->attach_solvers({&flow, &wall});
  EXPECT_EQ(flow.report_requests, 1);
  EXPECT_EQ(wall.report_requests, 1);
  c->initialize_step();
  wall.converged = true;
  c->update(residual(1.0));
  EXPECT_FALSE(c->is_satisfied());
  flow.converged = true;
  c->update(residual(1.0));
  EXPECT_TRUE(c->is_satisfied());
}

TEST(Convergence, SolverCouplingConvergenceOfASolverThatCannotReportIsAnErrorNamingIt) {
  auto c = make("type: solver_coupling_convergence\nsolver_index: 0");
  ReportingSolver flow("flow", false), wall("wall");
  try {
    c->attach_solvers({&flow, &wall});
    FAIL() << "no exception";
  } catch (const SolverError& e) {
    EXPECT_EQ(e.solver_name(), "flow");
    EXPECT_NE(std::string(e.what()).find("solver 'flow' cannot report whether its own "
                                         "iterations converged"),
              std::string::npos)
        << e.what();
  }
}

TEST(Convergence, SolverCouplingConvergenceNeedsSolverIndexZeroOrOne) {
  EXPECT_THROW(make("type: solver_coupling_convergence"), CaseError);
  EXPECT_THROW(make("type: solver_coupling_convergence\nsolver_index: 2"), CaseError);
}
