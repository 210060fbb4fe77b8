// TubeStructure: static ring deflection far from the clamped ends, and the time schemes.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "solvers/tube/tube_structure.hpp"
#include "tests/unit/solvers/tube/tube_test_parameters.hpp"

namespace cocopp::tube {
namespace {

constexpr double kPressure = 100.0;  // Pa

// Thin ring under uniform pressure: b3 dr = dp, dr = dp r0^2 (1 - nu^2) / (E h).
double ring_deflection(const TubeStructureParameters& parameters, double pressure) {
  const double r0 = parameters.geometry.radius();
  return pressure * r0 * r0 * (1.0 - parameters.nu * parameters.nu) / (parameters.e * parameters.h);
}

int middle_cell(const TubeStructure& structure) {
  return structure.cells() / 2;
}

TEST(TubeStructure, SteadyStateMatchesTheRingDeflectionAwayFromTheEnds) {
  const TubeStructureParameters parameters = testing::reference_structure(100);
  // A time step of 10 s makes the inertia term (rho_s h / dt^2 ~ 1e-2) negligible against
  // b3 ~ 1e7: one step gives the static solution.
  TubeStructure structure(parameters, 10.0);
  structure.initialize_step();
  const Eigen::VectorXd displacement =
      structure.solve(Eigen::VectorXd::Constant(100, kPressure + parameters.p_ref));
  const double expected = ring_deflection(parameters, kPressure);
  // The clamped ends disturb a bending boundary layer that decays like exp(-z / 1.7 mm)
  // (beam on an elastic foundation, (4 b1 / b3)^(1/4) = 1.7 mm). Cells more than 20 mm from
  // both ends (12 decay lengths) must agree to 1e-4, where exp(-12) = 6e-6 leaves margin.
  const Eigen::VectorXd z = structure.cell_centres();
  for (int i = 0; i < structure.cells(); ++i) {
    if (std::abs(z[i]) < 0.005) {
      EXPECT_NEAR(displacement[i], expected, 1e-4 * expected) << "z = " << z[i];
    }
  }
  // The clamped end holds the wall back.
  EXPECT_LT(displacement[0], 0.5 * expected);
}

// Solver-coupling convergence: the wall equation at the previous iterate, for the new pressure,
// below residual_atol. The equation is linear, so a repeated pressure leaves a residual of
// round-off and another pressure one of (its change) / (the diagonal) in metres.
TEST(TubeStructure, ReportsConvergenceWhenThePreviousIterateSolvesTheNewPressure) {
  TubeStructureParameters parameters = testing::reference_structure(100);
  EXPECT_THROW(TubeStructure(parameters, 1e-4).start_reporting_convergence(), std::runtime_error);
  parameters.residual_atol = 1e-12;
  TubeStructure structure(parameters, 1e-4);
  structure.start_reporting_convergence();
  structure.initialize_step();
  const Eigen::VectorXd pressure = Eigen::VectorXd::Constant(100, kPressure);
  structure.solve(pressure);
  EXPECT_FALSE(structure.converged_at_first_iteration());  // from the wall at rest
  structure.solve(pressure);
  EXPECT_TRUE(structure.converged_at_first_iteration());
  structure.solve(pressure * (1.0 + 1e-3));
  EXPECT_FALSE(structure.converged_at_first_iteration());
}

TEST(TubeStructure, BackwardEulerSettlesOnTheStaticDeflection) {
  const TubeStructureParameters parameters = testing::reference_structure(100);
  TubeStructure structure(parameters, 1e-4);
  const Eigen::VectorXd load = Eigen::VectorXd::Constant(100, kPressure);
  double middle = 0.0;
  // omega dt = 0.33: backward Euler multiplies the ring oscillation by 1/sqrt(1 + (omega dt)^2)
  // = 0.95 per step, so after 400 steps only the static deflection is left.
  for (int step = 1; step <= 400; ++step) {
    structure.initialize_step();
    middle = structure.solve(load)[middle_cell(structure)];
    structure.finalize_step();
  }
  EXPECT_NEAR(middle, ring_deflection(parameters, kPressure),
              1e-3 * ring_deflection(parameters, kPressure));
}

// The largest middle-cell displacement in the first and in the second period of the ring
// oscillation under a suddenly applied uniform pressure.
struct Maxima {
  double first_period = 0.0;
  int step_of_first = 0;
  double second_period = 0.0;
};

Maxima oscillation_maxima(const TubeStructureParameters& parameters, int steps_per_period) {
  // Ring frequency omega^2 = b3 / (rho_s h): the middle of a long tube moves like one ring.
  const double r0 = parameters.geometry.radius();
  const double omega = std::sqrt(
      parameters.e / ((1.0 - parameters.nu * parameters.nu) * r0 * r0 * parameters.rho_s));
  TubeStructure structure(parameters, 2.0 * kPi / omega / steps_per_period);
  const Eigen::VectorXd load = Eigen::VectorXd::Constant(structure.cells(), kPressure);
  Maxima maxima;
  for (int step = 1; step <= 2 * steps_per_period; ++step) {
    structure.initialize_step();
    const double middle = structure.solve(load)[middle_cell(structure)];
    structure.finalize_step();
    if (step <= steps_per_period && middle > maxima.first_period) {
      maxima.first_period = middle;
      maxima.step_of_first = step;
    }
    if (step > steps_per_period) maxima.second_period = std::max(maxima.second_period, middle);
  }
  return maxima;
}

// The clamped ends radiate dispersive bending waves after the sudden load; on the reference
// grid (dz = 0.5 mm) their short components reach the middle within two periods. A 0.5 m
// tube with 5 mm cells keeps them slow (group velocity < 3 m/s, 10 mm in two periods) and
// far from the middle cell.
TubeStructureParameters long_coarse_tube() {
  TubeStructureParameters parameters = testing::reference_structure(100);
  parameters.geometry.length = 0.5;
  return parameters;
}

TEST(TubeStructure, NewmarkKeepsTheRingOscillationUndamped) {
  TubeStructureParameters parameters = long_coarse_tube();
  parameters.time_scheme = TimeScheme::kNewmark;
  parameters.beta = 0.25;
  parameters.gamma = 0.5;
  const double static_deflection = ring_deflection(parameters, kPressure);
  const Maxima newmark = oscillation_maxima(parameters, 200);
  // A suddenly applied load: undamped oscillation between 0 and twice the static deflection,
  // first maximum after half a period. Average-acceleration Newmark conserves the amplitude;
  // its period error at 200 steps per period is (2 pi / 200)^2 / 12 = 8e-5.
  EXPECT_NEAR(newmark.first_period, 2.0 * static_deflection, 2e-3 * static_deflection);
  EXPECT_NEAR(newmark.step_of_first, 100, 1);
  EXPECT_NEAR(newmark.second_period, newmark.first_period, 2e-3 * static_deflection);
}

TEST(TubeStructure, BackwardEulerDampsTheRingOscillation) {
  const TubeStructureParameters parameters = long_coarse_tube();
  const double static_deflection = ring_deflection(parameters, kPressure);
  const Maxima euler = oscillation_maxima(parameters, 200);
  // Backward Euler multiplies the oscillation by 1 / sqrt(1 + (omega dt)^2) per step: 0.95
  // per half period and 0.905 per period at 200 steps per period.
  EXPECT_NEAR(euler.first_period, (1.0 + 0.952) * static_deflection, 5e-3 * static_deflection);
  EXPECT_NEAR(euler.second_period, (1.0 + 0.952 * 0.905) * static_deflection,
              5e-3 * static_deflection);
}

TEST(TubeStructure, VelocityAndAccelerationFollowTheTimeScheme) {
  TubeStructure structure(testing::reference_structure(20), 1e-4);
  const Eigen::VectorXd load = Eigen::VectorXd::Constant(20, kPressure);
  structure.initialize_step();
  const Eigen::VectorXd first = structure.solve(load);
  structure.finalize_step();
  // Backward Euler: r' = (r - r^n) / dt.
  EXPECT_TRUE(structure.radial_velocity().isApprox(first / 1e-4, 1e-12));
  structure.initialize_step();
  const Eigen::VectorXd second = structure.solve(load);
  structure.finalize_step();
  EXPECT_TRUE(structure.radial_velocity().isApprox((second - first) / 1e-4, 1e-9));
  EXPECT_TRUE(structure.radial_acceleration().isApprox(
      ((second - first) / 1e-4 - first / 1e-4) / 1e-4, 1e-6));
}

}  // namespace
}  // namespace cocopp::tube
