// TubeFlow: the analytic Jacobian against finite differences, the Newton solve, the inlet
// functions, rest, and output files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "solvers/tube/tube_flow.hpp"
#include "tests/unit/solvers/tube/tube_test_parameters.hpp"

namespace cocopp::tube {
namespace {

struct BoundaryCase {
  std::string name;
  InletBoundary inlet;
  OutletBoundary outlet;
  double initial_velocity;  ///< 0.1 with the +-0.2 perturbation gives flow in both directions
  /// Pa (m/s for a velocity inlet); the sine amplitude is a tenth of it
  double inlet_reference;
};

std::ostream& operator<<(std::ostream& stream, const BoundaryCase& c) {
  return stream << c.name;
}

class FlowJacobian : public ::testing::TestWithParam<BoundaryCase> {};

// A wall displacement that changes from step to step, so that old and new areas differ. Kept
// small: a fast wall motion pumps the inlet pressure above a prescribed total pressure.
Eigen::VectorXd wavy_displacement(const Eigen::VectorXd& z, double phase) {
  return (1e-7 * (300.0 * z.array() + phase).sin()).matrix();
}

TEST_P(FlowJacobian, EqualsFiniteDifferences) {
  const BoundaryCase& c = GetParam();
  TubeFlowParameters parameters = testing::reference_flow(12);
  parameters.u0 = c.initial_velocity;
  parameters.inlet = {c.inlet, InletFunction::kSine, c.inlet_reference, 0.1 * c.inlet_reference,
                      0.01};
  parameters.outlet = {c.outlet, 100.0};
  parameters.newtonmax = 5;
  TubeFlow flow(parameters, 1e-3);
  const Eigen::VectorXd z = flow.cell_centres();
  for (int step = 1; step <= 3; ++step) {
    flow.initialize_step();
    flow.solve(wavy_displacement(z, step));
    flow.finalize_step();
  }
  flow.initialize_step();
  flow.set_displacement(wavy_displacement(z, 4.0));

  // Perturb the state away from any solution, keeping every |u_i| > 0.02 so that the upwind
  // switch does not flip within a finite-difference step.
  Eigen::VectorXd x = flow.unknowns();
  for (int i = 0; i < x.size() / 2; ++i) {
    x[2 * i] += 0.2 * std::sin(1.7 * i + 0.3);
    if (std::abs(x[2 * i]) < 0.02) x[2 * i] += 0.05;
    x[2 * i + 1] += 0.05 * std::cos(0.9 * i);
  }

  const Eigen::MatrixXd analytic = flow.jacobian(x).to_dense();
  Eigen::MatrixXd finite_difference(x.size(), x.size());
  for (int j = 0; j < x.size(); ++j) {
    const double h = 1e-6 * std::max(1.0, std::abs(x[j]));
    Eigen::VectorXd plus = x, minus = x;
    plus[j] += h;
    minus[j] -= h;
    finite_difference.col(j) = (flow.residual(plus) - flow.residual(minus)) / (2.0 * h);
  }
  for (int i = 0; i < x.size(); ++i) {
    const double row_scale = analytic.row(i).cwiseAbs().maxCoeff();
    ASSERT_GT(row_scale, 0.0) << "row " << i;
    for (int j = 0; j < x.size(); ++j) {
      EXPECT_LE(std::abs(analytic(i, j) - finite_difference(i, j)), 1e-6 * row_scale)
          << "row " << i << ", column " << j << ": analytic " << analytic(i, j)
          << ", finite difference " << finite_difference(i, j);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    InletOutletTypes, FlowJacobian,
    ::testing::Values(
        BoundaryCase{"pressure_fixed", InletBoundary::kPressure, OutletBoundary::kFixed, 1.0,
                     500.0},
        BoundaryCase{"pressure_non_reflecting", InletBoundary::kPressure,
                     OutletBoundary::kNonReflecting, 0.1, 500.0},
        BoundaryCase{"velocity_fixed", InletBoundary::kVelocity, OutletBoundary::kFixed, -1.0,
                     -1.0},
        BoundaryCase{"velocity_non_reflecting", InletBoundary::kVelocity,
                     OutletBoundary::kNonReflecting, 1.0, 1.0},
        // Total pressure close to p + rho_f u0^2 / 2 of the initial state: far from it, the
        // first Newton step takes the inlet pressure above the total pressure.
        BoundaryCase{"total_pressure_fixed", InletBoundary::kTotalPressure, OutletBoundary::kFixed,
                     1.0, 600.0},
        BoundaryCase{"total_pressure_non_reflecting", InletBoundary::kTotalPressure,
                     OutletBoundary::kNonReflecting, 1.0, 600.0}),
    [](const ::testing::TestParamInfo<BoundaryCase>& info) { return info.param.name; });

TEST(TubeFlow, NewtonConvergesQuadratically) {
  TubeFlowParameters parameters = testing::reference_flow(100);
  parameters.u0 = 1.0;
  parameters.inlet = {InletBoundary::kVelocity, InletFunction::kSine, 1.0, 0.1, 1.0};
  parameters.outlet = {OutletBoundary::kNonReflecting, 0.0};
  parameters.newtonmax = 20;
  parameters.newtontol = 1e-12;
  TubeFlow flow(parameters, 0.01);
  const Eigen::VectorXd z = flow.cell_centres();
  for (int step = 1; step <= 5; ++step) {
    flow.initialize_step();
    flow.solve(wavy_displacement(z, step));
    EXPECT_LT(flow.relative_residual(), 1e-12) << "step " << step;
    EXPECT_LE(flow.newton_iterations(), 6) << "step " << step;
    flow.finalize_step();
  }
}

TEST(TubeFlow, RepeatedIterationWithTheSameInputIsUnchanged) {
  TubeFlowParameters parameters = testing::reference_flow(50);
  parameters.newtonmax = 10;
  parameters.newtontol = 1e-13;
  TubeFlow flow(parameters, 1e-4);
  flow.initialize_step();
  const Eigen::VectorXd displacement = wavy_displacement(flow.cell_centres(), 0.0);
  const Eigen::VectorXd first = flow.solve(displacement);
  const Eigen::VectorXd second = flow.solve(displacement);
  EXPECT_LT((second - first).norm(), 1e-10 * first.norm());
}

// Solver-coupling convergence: a coupling iteration whose previous iterate already meets
// newtontol for the new displacement needs no Newton step; never the step's first.
TEST(TubeFlow, ReportsConvergenceAtTheFirstIterationOnlyWhenTheInputStaysTheSame) {
  TubeFlowParameters parameters = testing::reference_flow(50);
  parameters.newtonmax = 10;
  parameters.newtontol = 1e-8;
  TubeFlow flow(parameters, 1e-4);
  flow.initialize_step();
  const Eigen::VectorXd displacement = wavy_displacement(flow.cell_centres(), 0.0);
  flow.solve(displacement);
  EXPECT_FALSE(flow.converged_at_first_iteration());  // the step's first solve
  flow.solve(1.5 * displacement);
  EXPECT_FALSE(flow.converged_at_first_iteration());
  EXPECT_GT(flow.newton_iterations(), 0);
  flow.solve(1.5 * displacement);
  EXPECT_TRUE(flow.converged_at_first_iteration());
  flow.finalize_step();
  flow.initialize_step();
  flow.solve(1.5 * displacement);
  EXPECT_FALSE(flow.converged_at_first_iteration());  // a new step starts unconverged
}

TEST(TubeFlow, FluidAtRestStaysAtRest) {
  TubeFlowParameters parameters = testing::reference_flow(20);
  parameters.inlet = {InletBoundary::kPressure, InletFunction::kConstant, 0.0, 0.0, 0.0};
  TubeFlow flow(parameters, 1e-4);
  const Eigen::VectorXd no_displacement = Eigen::VectorXd::Zero(20);
  for (int step = 1; step <= 10; ++step) {
    flow.initialize_step();
    const Eigen::VectorXd pressure = flow.solve(no_displacement);
    flow.finalize_step();
    EXPECT_EQ(pressure.cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(flow.velocity().cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(flow.newton_iterations(), 0);
  }
}

// The spec skips Newton when f0 = 0; a later iteration of the same step with a different
// input must still be solved (f0 is then the first nonzero residual of the step).
TEST(TubeFlow, IterationAfterAnExactFirstIterationIsSolved) {
  TubeFlowParameters parameters = testing::reference_flow(20);
  parameters.inlet = {InletBoundary::kPressure, InletFunction::kConstant, 0.0, 0.0, 0.0};
  parameters.newtonmax = 10;
  parameters.newtontol = 1e-12;
  TubeFlow flow(parameters, 1e-4);
  flow.initialize_step();
  flow.solve(Eigen::VectorXd::Zero(20));
  EXPECT_EQ(flow.newton_iterations(), 0);
  flow.solve(Eigen::VectorXd::Constant(20, 1e-7));
  EXPECT_GT(flow.newton_iterations(), 0);
  EXPECT_LT(flow.relative_residual(), 1e-12);
}

TEST(TubeFlow, InitialStateAndPressureUnits) {
  TubeFlowParameters parameters = testing::reference_flow(10);
  parameters.u0 = 0.5;
  parameters.p_ref = 200.0;
  const TubeFlow flow(parameters, 1e-4);
  EXPECT_TRUE(flow.pressure().isApprox(Eigen::VectorXd::Constant(10, 200.0)));
  EXPECT_TRUE(flow.velocity().isApprox(Eigen::VectorXd::Constant(10, 0.5)));
  EXPECT_NEAR(flow.cell_centres()[0], -0.025 + 0.0025, 1e-15);
  EXPECT_NEAR(flow.cell_centres()[9], 0.025 - 0.0025, 1e-15);
}

TEST(TubeFlow, PressureInletIsImposedExactly) {
  TubeFlow flow(testing::reference_flow(100), 1e-4);
  flow.initialize_step();
  flow.solve(Eigen::VectorXd::Zero(100));
  EXPECT_DOUBLE_EQ(flow.unknowns()[1] * 1000.0, 1333.2);
}

TEST(InletParameters, TimeFunctions) {
  const double dt = 1e-4;
  InletParameters pulse{InletBoundary::kPressure, InletFunction::kPulse, 10.0, 1333.2, 0.003};
  EXPECT_DOUBLE_EQ(pulse.value(1, dt), 1343.2);
  EXPECT_DOUBLE_EQ(pulse.value(30, dt), 1343.2);  // 0.003 / 1e-4 = 29.999... in binary
  EXPECT_DOUBLE_EQ(pulse.value(31, dt), 10.0);

  InletParameters sine{InletBoundary::kVelocity, InletFunction::kSine, 1.0, 0.1, 1.0};
  EXPECT_NEAR(sine.value(25, 0.01), 1.1, 1e-15);
  EXPECT_NEAR(sine.value(50, 0.01), 1.0, 1e-15);

  InletParameters sin2{InletBoundary::kPressure, InletFunction::kSin2, 0.0, 2.0, 1.0};
  EXPECT_NEAR(sin2.value(50, 0.01), 2.0, 1e-15);
  EXPECT_NEAR(sin2.value(25, 0.01), 1.0, 1e-15);

  InletParameters ramp{InletBoundary::kPressure, InletFunction::kRamp, 1.0, 4.0, 2.0};
  EXPECT_NEAR(ramp.value(50, 0.01), 2.0, 1e-15);

  InletParameters constant{InletBoundary::kPressure, InletFunction::kConstant, 1.0, 4.0, 0.0};
  EXPECT_DOUBLE_EQ(constant.value(7, 0.01), 5.0);
}

TEST(TubeFlow, WritesParaViewFilesAtTheOutputInterval) {
  const std::filesystem::path directory =
      std::filesystem::temp_directory_path() / "cocopp_tube_flow_output_test";
  std::filesystem::remove_all(directory);
  TubeFlowParameters parameters = testing::reference_flow(5);
  parameters.output = {2, directory.string()};
  TubeFlow flow(parameters, 1e-4);
  for (int step = 1; step <= 4; ++step) {
    flow.initialize_step();
    flow.solve(Eigen::VectorXd::Constant(5, 1e-6));
    flow.finalize_step();
    flow.output_step(step, step * 1e-4);
  }
  EXPECT_FALSE(std::filesystem::exists(directory / "tube_flow_000001.vtk"));
  EXPECT_TRUE(std::filesystem::exists(directory / "tube_flow_000002.vtk"));
  std::ifstream file(directory / "tube_flow_000004.vtk");
  std::stringstream text;
  text << file.rdbuf();
  EXPECT_NE(text.str().find("DATASET POLYDATA"), std::string::npos);
  // The time, for ParaView's file series: TIME field data.
  EXPECT_NE(text.str().find("FIELD FieldData 1\nTIME 1 1 double\n0.00040000000000000002\n"),
            std::string::npos)
      << text.str();
  EXPECT_NE(text.str().find("POINTS 5 double"), std::string::npos);
  EXPECT_NE(text.str().find("SCALARS pressure double 1"), std::string::npos);
  EXPECT_NE(text.str().find("SCALARS velocity double 1"), std::string::npos);
  // First point: (0, r0 + dr, z_1).
  EXPECT_NE(text.str().find("0 0.0050010000000000002 -0.02"), std::string::npos) << text.str();
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace cocopp::tube
