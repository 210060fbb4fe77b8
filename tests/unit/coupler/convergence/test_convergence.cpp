// Convergence criteria and their combinations.
#include <gtest/gtest.h>

#include "coupler/convergence/convergence_criterion.hpp"

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
