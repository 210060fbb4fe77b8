// TubeRingmodel against its closed-form tube law.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "solvers/tube/tube_ringmodel.hpp"
#include "tests/unit/solvers/tube/tube_test_parameters.hpp"

namespace cocopp::tube {
namespace {

TEST(TubeRingmodel, FollowsTheTubeLaw) {
  TubeRingmodelParameters parameters = testing::reference_ringmodel(50);
  parameters.p_ref = 500.0;
  TubeRingmodel rings(parameters);
  const double rho_f = 1000.0, r0 = 0.005;
  const double c02 = 3e5 * 1e-3 / (rho_f * 0.01) - 500.0 / (2.0 * rho_f);
  Eigen::VectorXd pressure(50);
  for (int i = 0; i < 50; ++i) pressure[i] = -20000.0 + 1000.0 * i;  // up to 29 kPa
  const Eigen::VectorXd displacement = rings.solve(pressure);
  for (int i = 0; i < 50; ++i) {
    // Inverse of the tube law: p = p_ref + 2 rho_f c0^2 (1 - r0 / r).
    const double radius = r0 + displacement[i];
    const double recovered = 500.0 + 2.0 * rho_f * c02 * (1.0 - r0 / radius);
    EXPECT_NEAR(recovered, pressure[i], 1e-10 * std::abs(pressure[i]) + 1e-9) << "cell " << i;
    // Forward law written out: dr = r0 (2 / (2 + (p_ref - p) / (rho_f c0^2)) - 1).
    const double expected = r0 * (2.0 / (2.0 + (500.0 - pressure[i]) / (rho_f * c02)) - 1.0);
    EXPECT_NEAR(displacement[i], expected, 1e-14 * r0) << "cell " << i;
  }
}

TEST(TubeRingmodel, SmallPressuresGiveTheThinWallDeflection) {
  TubeRingmodel rings(testing::reference_ringmodel(3));
  const double pressure = 10.0;  // Pa, small against rho_f c^2 = 30 kPa
  const double displacement = rings.displacement_at(pressure);
  // Linear thin-walled tube: dr = p r0^2 / (E h); the tube law agrees to O(p / (rho_f c^2)).
  const double linear = pressure * 0.005 * 0.005 / (3e5 * 1e-3);
  EXPECT_NEAR(displacement, linear, 1e-3 * linear);
  EXPECT_EQ(rings.displacement_at(0.0), 0.0);
}

// Solver-coupling convergence: the new pressure moves the wall by less than residual_atol.
TEST(TubeRingmodel, ReportsConvergenceWhenThePressureNoLongerMovesTheWall) {
  TubeRingmodelParameters parameters = testing::reference_ringmodel(10);
  EXPECT_THROW(TubeRingmodel(parameters).start_reporting_convergence(), std::runtime_error);
  parameters.residual_atol = 1e-12;
  TubeRingmodel wall(parameters);
  wall.start_reporting_convergence();
  const Eigen::VectorXd pressure = Eigen::VectorXd::Constant(10, 100.0);
  wall.solve(pressure);
  EXPECT_FALSE(wall.converged_at_first_iteration());
  wall.solve(pressure);
  EXPECT_TRUE(wall.converged_at_first_iteration());
  wall.solve(1.01 * pressure);
  EXPECT_FALSE(wall.converged_at_first_iteration());
}

TEST(TubeRingmodel, UnphysicalPressureThrows) {
  TubeRingmodel rings(testing::reference_ringmodel(4));
  // Limit: p / rho_f < 2 c0^2 + p_ref / rho_f, i.e. p < 60 kPa here.
  EXPECT_NO_THROW(rings.displacement_at(59999.0));
  Eigen::VectorXd pressure = Eigen::VectorXd::Zero(4);
  pressure[2] = 60001.0;
  try {
    rings.solve(pressure);
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("unphysical pressure"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace cocopp::tube
