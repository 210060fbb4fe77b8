// The component registries: creation by `type`, and errors for unknown types.
#include <gtest/gtest.h>

#include "coupler/convergence/convergence_criterion.hpp"
#include "coupler/coupled_solvers/coupled_solver.hpp"
#include "coupler/predictors/predictor.hpp"

using namespace cocopp;

TEST(Registry, EveryComponentOfTheCoreIssueIsRegistered) {
  const auto coupled = CoupledSolverRegistry::instance().names();
  for (const char* name : {"explicit", "gauss_seidel", "relaxation", "aitken", "iqni"})
    EXPECT_NE(std::find(coupled.begin(), coupled.end(), name), coupled.end()) << name;
  const auto predictors = PredictorRegistry::instance().names();
  for (const char* name : {"constant", "linear", "legacy", "quadratic", "cubic"})
    EXPECT_NE(std::find(predictors.begin(), predictors.end(), name), predictors.end()) << name;
  const auto criteria = ConvergenceCriterionRegistry::instance().names();
  for (const char* name : {"absolute_norm", "relative_norm", "iteration_limit", "and", "or"})
    EXPECT_NE(std::find(criteria.begin(), criteria.end(), name), criteria.end()) << name;
}

TEST(Registry, UnknownTypeSuggestsAndLists) {
  const Settings s = Settings::load_string("predictor:\n  type: lineair\n", "case.yaml");
  try {
    PredictorRegistry::instance().create(s.child("predictor"));
    FAIL() << "no error";
  } catch (const CaseError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("case.yaml:2:"), std::string::npos) << message;
    EXPECT_NE(message.find("unknown predictor 'lineair'; did you mean 'linear'?"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find("available: constant, cubic"), std::string::npos) << message;
  }
}

TEST(Registry, MissingTypeIsAnError) {
  const Settings s = Settings::load_string("predictor:\n  order: 2\n", "case.yaml");
  EXPECT_THROW(PredictorRegistry::instance().create(s.child("predictor")), CaseError);
}
