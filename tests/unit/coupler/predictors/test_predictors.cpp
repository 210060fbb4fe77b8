// Predictors extrapolate polynomials of their order exactly, and fall back with short history.
#include <gtest/gtest.h>

#include "coupler/predictors/predictor.hpp"

using namespace cocopp;

namespace {

std::unique_ptr<Predictor> make(const std::string& type) {
  return PredictorRegistry::instance().create(Settings::load_string("type: " + type, "p.yaml"));
}

/// Feed f(0), f(1), ..., f(steps) and return the prediction for f(steps + 1).
double predict_after(Predictor& p, int steps, double (*f)(double)) {
  p.initialize(Eigen::VectorXd::Constant(1, f(0)));
  for (int n = 1; n <= steps; ++n) p.update(Eigen::VectorXd::Constant(1, f(n)));
  return p.predict()(0);
}

double constant(double) {
  return 3.0;
}
double linear(double t) {
  return 1.0 + 2.0 * t;
}
double quadratic(double t) {
  return 1.0 - t + 0.5 * t * t;
}
double cubic(double t) {
  return 2.0 + t - t * t + 0.25 * t * t * t;
}

}  // namespace

TEST(Predictors, ExactForTheirPolynomialOrder) {
  EXPECT_DOUBLE_EQ(predict_after(*make("constant"), 5, constant), 3.0);
  EXPECT_NEAR(predict_after(*make("linear"), 5, linear), linear(6), 1e-12);
  EXPECT_NEAR(predict_after(*make("quadratic"), 5, quadratic), quadratic(6), 1e-12);
  EXPECT_NEAR(predict_after(*make("cubic"), 5, cubic), cubic(6), 1e-12);
}

TEST(Predictors, LegacyWeights) {
  auto p = make("legacy");
  p->initialize(Eigen::VectorXd::Constant(1, 1.0));  // x^(n-2)
  p->update(Eigen::VectorXd::Constant(1, 2.0));      // x^(n-1)
  p->update(Eigen::VectorXd::Constant(1, 5.0));      // x^n
  EXPECT_DOUBLE_EQ(p->predict()(0), 2.5 * 5.0 - 2.0 * 2.0 + 0.5 * 1.0);
}

TEST(Predictors, FallBackToLowerOrderWithShortHistory) {
  auto cubic_predictor = make("cubic");
  cubic_predictor->initialize(Eigen::VectorXd::Constant(1, 4.0));
  EXPECT_DOUBLE_EQ(cubic_predictor->predict()(0), 4.0);  // constant
  cubic_predictor->update(Eigen::VectorXd::Constant(1, 5.0));
  EXPECT_DOUBLE_EQ(cubic_predictor->predict()(0), 6.0);  // linear
  cubic_predictor->update(Eigen::VectorXd::Constant(1, 7.0));
  EXPECT_DOUBLE_EQ(cubic_predictor->predict()(0), 3 * 7.0 - 3 * 5.0 + 4.0);  // quadratic
  EXPECT_EQ(cubic_predictor->history().size(), 3u);
}
