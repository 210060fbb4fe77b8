// Per-variable scaling on an interface that carries pressure (order 1e6) next to traction
// (order 1): the loads are the unknowns x (the structure runs first), a common set-up when
// the structure prescribes the displacement.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "coupler/coupled_solvers/coupled_solver.hpp"
#include "coupler/coupled_solvers/scaling.hpp"
#include "tests/support/linear_solvers.hpp"

using namespace cocopp;
using cocopp::testing::FlatAffineSolver;

namespace {

constexpr int kPoints = 4;
constexpr double kPressureScale = 1e6;

/// x = [pressure; traction] on kPoints points (16 unknowns); the structure maps x to a
/// displacement and temperature of order 1 (any 16 values), the "flow" maps those back. The coupled
/// map x -> S(F(x)) = T C0 T^-1 x + d, with C0 symmetric with eigenvalues in [-80, -1.2] (Gauss-
/// Seidel diverges) and T = diag(1e6 on pressure, 1 on traction).
struct LoadsProblem {
  LoadsProblem() {
    auto part = cocopp::testing::line_model_part(kPoints);
    const Interface loads({{part, {"pressure", "traction"}}});
    const Interface motion({{part, {"displacement", "temperature"}}});
    const Eigen::Index n = loads.size();
    std::srand(3);
    const Eigen::MatrixXd q = Eigen::MatrixXd::Random(n, n).householderQr().householderQ();
    const Eigen::VectorXd eigenvalues = Eigen::VectorXd::LinSpaced(n, -80.0, -1.2);
    Eigen::VectorXd t = Eigen::VectorXd::Ones(n);
    t.head(kPoints).setConstant(kPressureScale);  // pressure comes first in the layout
    const Eigen::MatrixXd c0 = q * eigenvalues.asDiagonal() * q.transpose();
    const Eigen::VectorXd offset = t.cwiseProduct(Eigen::VectorXd::LinSpaced(n, 1.0, 2.0));
    // First solver: loads -> motion of order 1 (T^-1); second: motion -> loads (T C0).
    first = std::make_unique<FlatAffineSolver>("structure", loads, motion,
                                               Eigen::MatrixXd(t.cwiseInverse().asDiagonal()),
                                               Eigen::VectorXd::Zero(n));
    second = std::make_unique<FlatAffineSolver>("flow", motion, loads, t.asDiagonal() * c0, offset);
    const Eigen::MatrixXd coupling = t.asDiagonal() * c0 * t.cwiseInverse().asDiagonal();
    solution = (Eigen::MatrixXd::Identity(n, n) - coupling).lu().solve(offset);
  }
  std::unique_ptr<FlatAffineSolver> first, second;
  Eigen::VectorXd solution;
};

/// Iterations until both variables are within 1e-8 (relative, each on its own scale) of the
/// solution, or -1 if that does not happen within 60.
int iterations_to_solve(const std::string& coupled_solver_settings) {
  LoadsProblem problem;
  const std::string yaml = coupled_solver_settings +
                           "\npredictor: {type: constant}\n"
                           "convergence_criterion: {type: iteration_limit, maximum: 1}\n";
  const Eigen::Index p = kPoints;
  const Eigen::VectorXd& exact = problem.solution;
  for (int limit = 1; limit <= 60; ++limit) {
    LoadsProblem fresh;
    std::string with_limit = yaml;
    with_limit.replace(with_limit.find("maximum: 1"), 10, "maximum: " + std::to_string(limit));
    auto coupled =
        CoupledSolverRegistry::instance().create(Settings::load_string(with_limit, "case.yaml"));
    coupled->initialize(*fresh.first, *fresh.second);
    try {
      coupled->solve_step(1, 0.1);
    } catch (const DivergenceError&) {
      return -1;
    }
    const Eigen::VectorXd x = coupled->x().data();
    const double pressure_error = (x.head(p) - exact.head(p)).norm() / exact.head(p).norm();
    const double traction_error =
        (x.tail(3 * p) - exact.tail(3 * p)).norm() / exact.tail(3 * p).norm();
    if (pressure_error < 1e-8 && traction_error < 1e-8) return limit;
  }
  return -1;
}

}  // namespace

TEST(Scaling, LetsTheSmallVariableThroughTheRelativeFilter) {
  // preCICE's default QR filter relative to the column norm: unweighted, a column whose new
  // information is in the traction is 1e-6 of its (pressure-dominated) norm and is dropped.
  const std::string iqn =
      "type: iqni\nomega: 0.01\nmodel: {type: ls, min_significant: 0, "
      "min_significant_relative: 1e-3}";
  const int unscaled = iterations_to_solve(iqn);
  const int fixed = iterations_to_solve(iqn + "\nscaling: {pressure: 1e-6}");
  const int automatic = iterations_to_solve(iqn + "\nscaling: automatic");
  // 16 unknowns: n + 1 columns' worth of iterations, plus the relaxed first one.
  EXPECT_GT(fixed, 0);
  EXPECT_LE(fixed, 18);
  EXPECT_GT(automatic, 0);
  EXPECT_LE(automatic, 18);
  // Measured: 38 unscaled against 18 with either scaling.
  EXPECT_TRUE(unscaled == -1 || unscaled > fixed + 10) << unscaled << " vs " << fixed;
}

TEST(Scaling, IbqnWeightsItsModelsInputs) {
  const std::string ibqn =
      "type: ibqn\nomega: 0.01\nmodel_f: {type: ls, min_significant: 0, "
      "min_significant_relative: 1e-3}\nmodel_s: {type: ls, min_significant: 0, "
      "min_significant_relative: 1e-3}";
  const int unscaled = iterations_to_solve(ibqn);
  const int scaled = iterations_to_solve(ibqn + "\nscaling: {pressure: 1e-6}");
  EXPECT_GT(scaled, 0);
  EXPECT_LE(scaled, 19);
  // Measured: 57 unscaled.
  EXPECT_TRUE(unscaled == -1 || unscaled > scaled + 10) << unscaled << " vs " << scaled;
}

TEST(Scaling, UnknownVariableIsAnErrorWithSuggestion) {
  LoadsProblem problem;
  auto coupled = CoupledSolverRegistry::instance().create(Settings::load_string(
      "type: iqni\nmodel: {type: ls}\nscaling: {presure: 1e-6}\npredictor: {type: constant}\n"
      "convergence_criterion: {type: iteration_limit, maximum: 3}\n",
      "case.yaml"));
  try {
    coupled->initialize(*problem.first, *problem.second);
    FAIL() << "expected an error";
  } catch (const CaseError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("case.yaml:3"), std::string::npos) << message;
    EXPECT_NE(message.find("did you mean 'pressure'"), std::string::npos) << message;
  }
}

TEST(Scaling, AutomaticWeightsComeFromTheFirstNonZeroValuesAndStay) {
  auto part = cocopp::testing::line_model_part(2);
  const Interface layout({{part, {"pressure", "traction"}}});
  VariableScaling scaling(Settings::load_string("scaling: automatic", "case.yaml"));
  scaling.bind({&layout});
  Eigen::VectorXd values = Eigen::VectorXd::Zero(layout.size());
  values.head(2) << 3e5, 4e5;  // pressure RMS sqrt((9 + 16) / 2) 1e5; traction still zero
  Eigen::VectorXd weighted = scaling.apply(0, values);
  EXPECT_NEAR(weighted(0), 3.0 / std::sqrt(12.5), 1e-12);
  EXPECT_EQ(scaling.weights().count("traction"), 0u);
  values.tail(6).setConstant(2.0);
  values.head(2) *= 10.0;  // later values do not change a fixed weight
  weighted = scaling.apply(0, values);
  EXPECT_NEAR(weighted(0), 30.0 / std::sqrt(12.5), 1e-12);
  EXPECT_NEAR(weighted(5), 1.0, 1e-15);
}
