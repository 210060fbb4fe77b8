// A pressure front in the flow solver coupled to the ring model travels at the Moens-Korteweg
// speed c = sqrt(E h / (rho_f d)).
//
// The coupling inside this test is a Newton iteration on the wall displacement with the
// flow's interface Jacobian d(pressure)/d(displacement) taken by finite differences at the
// first time step and then kept. Fixed-point iterations (relaxed, Aitken) are useless here:
// at dt = 2e-5 s the Gauss-Seidel error amplification of the lowest wall mode is
// 1 / (k_1 c dt)^2 ~ 2e4 (docs: "Why Gauss-Seidel diverges"), and Aitken did not reach 1e-8
// in 2000 iterations per step. Newton needs at most a handful.
#include <gtest/gtest.h>

#include <cmath>

#include "solvers/tube/tube_flow.hpp"
#include "solvers/tube/tube_ringmodel.hpp"
#include "tests/unit/solvers/tube/tube_test_parameters.hpp"

namespace cocopp::tube {
namespace {

// d(pressure)/d(displacement) of one flow iteration, probing copies of `flow` so that its
// state (and its f0 of this time step) is left alone.
Eigen::MatrixXd flow_interface_jacobian(const TubeFlow& flow, const Eigen::VectorXd& displacement,
                                        const Eigen::VectorXd& pressure) {
  const double step = 1e-10;  // m; the displacements here are ~1e-6 m
  Eigen::MatrixXd jacobian(pressure.size(), displacement.size());
  for (Eigen::Index j = 0; j < displacement.size(); ++j) {
    TubeFlow probe = flow;
    Eigen::VectorXd perturbed = displacement;
    perturbed[j] += step;
    jacobian.col(j) = (probe.solve(perturbed) - pressure) / step;
  }
  return jacobian;
}

// d(displacement)/d(pressure) of the ring model: a diagonal.
Eigen::VectorXd ring_derivative(const TubeRingmodel& rings, const Eigen::VectorXd& pressure) {
  const double step = 1e-3;  // Pa
  Eigen::VectorXd derivative(pressure.size());
  for (Eigen::Index i = 0; i < pressure.size(); ++i) {
    derivative[i] =
        (rings.displacement_at(pressure[i] + step) - rings.displacement_at(pressure[i] - step)) /
        (2.0 * step);
  }
  return derivative;
}

// Linear interpolation of the time at which `value` rose through `level` during step n.
double crossing_time(double previous, double value, double level, int n, double delta_t) {
  return delta_t * (n - 1 + (level - previous) / (value - previous));
}

TEST(TubeWaveSpeed, PressureFrontTravelsAtTheMoensKortewegSpeed) {
  const int cells = 100;
  const double delta_t = 2e-5;
  const double amplitude = 100.0;  // Pa: small against rho_f c^2 = 30 kPa, so nearly linear
  TubeFlowParameters flow_parameters = testing::reference_flow(cells);
  flow_parameters.inlet = {InletBoundary::kPressure, InletFunction::kConstant, 0.0, amplitude, 0.0};
  flow_parameters.outlet = {OutletBoundary::kNonReflecting, 0.0};
  flow_parameters.newtonmax = 10;
  flow_parameters.newtontol = 1e-13;
  TubeFlow flow(flow_parameters, delta_t);
  TubeRingmodel rings(testing::reference_ringmodel(cells));

  // Probes a quarter of the length from each end, 50 cells (25 mm) apart.
  const int first_probe = cells / 4, second_probe = 3 * cells / 4;
  double first_arrival = -1.0, second_arrival = -1.0;
  double first_previous = 0.0, second_previous = 0.0;
  Eigen::VectorXd displacement = Eigen::VectorXd::Zero(cells);
  Eigen::MatrixXd flow_jacobian;
  int most_iterations = 0;
  for (int n = 1; n <= 400; ++n) {  // 8 ms: the front reaches the second probe at ~7 ms
    flow.initialize_step();
    rings.initialize_step();
    Eigen::VectorXd pressure = flow.solve(displacement);
    if (n == 1) flow_jacobian = flow_interface_jacobian(flow, displacement, pressure);
    int iteration = 0;
    for (;; ++iteration) {
      const Eigen::VectorXd residual = rings.solve(pressure) - displacement;
      // 1e-8: the flow's Newton tolerance (1e-13) times the ~2e4 amplification above.
      if (residual.norm() <= 1e-8 * rings.displacement().norm()) break;
      ASSERT_LT(iteration, 20) << "coupling did not converge in step " << n;
      const Eigen::MatrixXd coupled_jacobian =
          ring_derivative(rings, pressure).asDiagonal() * flow_jacobian -
          Eigen::MatrixXd::Identity(cells, cells);
      displacement -= coupled_jacobian.partialPivLu().solve(residual);
      pressure = flow.solve(displacement);
    }
    most_iterations = std::max(most_iterations, iteration);
    flow.finalize_step();
    rings.finalize_step();

    const double level = amplitude / 2.0;  // the middle of the front
    if (first_arrival < 0.0 && pressure[first_probe] >= level) {
      first_arrival = crossing_time(first_previous, pressure[first_probe], level, n, delta_t);
    }
    if (second_arrival < 0.0 && pressure[second_probe] >= level) {
      second_arrival = crossing_time(second_previous, pressure[second_probe], level, n, delta_t);
    }
    first_previous = pressure[first_probe];
    second_previous = pressure[second_probe];
  }
  ASSERT_GT(first_arrival, 0.0);
  ASSERT_GT(second_arrival, first_arrival);
  const Eigen::VectorXd z = flow.cell_centres();
  const double speed = (z[second_probe] - z[first_probe]) / (second_arrival - first_arrival);
  const double moens_korteweg = std::sqrt(3e5 * 1e-3 / (1000.0 * 0.01));
  // The upwind/implicit scheme smears the front symmetrically, so its middle moves at c; the
  // remaining error is dispersion and the nonlinearity of the tube law (~p / (rho_f c^2)):
  // measured 0.06 % at 50 cells per 25 mm and c dt / dz = 0.22. 1 % leaves room for other
  // platforms' round-off while still catching a wrong wave speed (e.g. a factor in cmk2).
  EXPECT_NEAR(speed / moens_korteweg, 1.0, 0.01)
      << "front speed " << speed << " m/s, Moens-Korteweg " << moens_korteweg << " m/s";
  EXPECT_LE(most_iterations, 10);
}

}  // namespace
}  // namespace cocopp::tube
