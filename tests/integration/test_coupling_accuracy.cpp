// Accuracy against references, on whole example runs (ctest label long: the Release pass only,
// not the sanitizer's; the code paths they take are covered by test_substeps.cpp and
// test_solver_group.cpp):
// - substeps: the flow at a quarter of the coupling step, the structure at the step, is closer
//   to a fully resolved run than both at the step (bench/substeps.py has the whole table); the
//   interpolation in time on its own (massless rings: the wall's answer is exact at any time):
//   quadratic's difference to coupling every substep falls as the step does, linear's does not;
// - a group of two walls of different stiffness reflects and transmits a wave as acoustics
//   says.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "tests/integration/run_helpers.hpp"
#include "tests/integration/variant_runs.hpp"

using namespace cocopp::testing;
namespace fs = std::filesystem;

namespace {

TEST(Substeps, AFlowAtAQuarterOfTheStepComesCloserToTheResolvedRun) {
  const fs::path resolved =
      run_variant("tube/flow_structure", "substeps_resolved", {6.25e-6, 1600});
  const fs::path coarse = run_variant("tube/flow_structure", "substeps_coarse", {1e-4, 100});
  const fs::path flow4 =
      run_variant("tube/flow_structure", "substeps_flow4", {1e-4, 100, 4, 1, "quadratic", true});
  const fs::path end_values =
      run_variant("tube/flow_structure", "substeps_end_values", {1e-4, 100, 4, 1, "linear", false});
  const auto reference = radial(resolved, 16);
  const double both = relative_difference(reference, radial(coarse));
  const double substepped = relative_difference(reference, radial(flow4));
  const double without_mean = relative_difference(reference, radial(end_values));
  // Measured: 0.237 both at the step, 0.160 the flow substepped (quadratic, the loads' mean to
  // the structure), 1.39 with the loads' end values: the structure misses the impulse the
  // flow's first substep passes on when the wall's motion turns.
  EXPECT_NEAR(both, 0.237, 0.01);
  EXPECT_LT(substepped, 0.75 * both);
  EXPECT_GT(without_mean, 2.0 * both);
  for (const auto& dir : {resolved, coarse, flow4, end_values}) fs::remove_all(dir);
}

TEST(Substeps, QuadraticInterpolationConvergesToCouplingEverySubstep) {
  // The ring model answers at any time exactly, so the difference to coupling every substep is
  // the interpolation's. Steps shorter than a pressure wave's way along the tube (9 ms), over
  // 0.1 s, the difference after the start-up (from 0.05 s). Measured: quadratic 2.41e-5,
  // 1.18e-5, 5.61e-6 for steps of 2, 1, 0.5 ms (order 1.03, 1.07); linear 1.33e-3, 1.19e-3,
  // 1.11e-3: the flow answers the wall's acceleration, which is zero inside a piecewise-linear
  // window (docs/coupling.md, "Order in time").
  const auto after_start_up = [](std::vector<double> values, double delta_t) {
    const auto start_up = static_cast<std::ptrdiff_t>(100 * std::lround(0.05 / delta_t));
    values.erase(values.begin(), values.begin() + start_up);
    return values;
  };
  std::vector<double> quadratic, linear;
  for (const double delta_t : {0.002, 0.001, 0.0005}) {
    const int steps = static_cast<int>(std::lround(0.1 / delta_t));
    const fs::path every =
        run_variant("tube/flow_ringmodel", "order_every", {delta_t / 4, 4 * steps}, 1e-12);
    const auto reference = after_start_up(radial(every, 4), delta_t);
    fs::remove_all(every);
    for (const std::string interpolation : {"quadratic", "linear"}) {
      if (interpolation == "linear" && delta_t == 0.001) continue;
      const fs::path substepped = run_variant("tube/flow_ringmodel", "order_" + interpolation,
                                              {delta_t, steps, 4, 1, interpolation, false}, 1e-12);
      (interpolation == "linear" ? linear : quadratic)
          .push_back(relative_difference(reference, after_start_up(radial(substepped), delta_t)));
      fs::remove_all(substepped);
    }
  }
  EXPECT_GT(quadratic[0] / quadratic[1], 1.8) << quadratic[0] << " " << quadratic[1];
  EXPECT_GT(quadratic[1] / quadratic[2], 1.8) << quadratic[1] << " " << quadratic[2];
  EXPECT_LT(quadratic[2], 1e-5);
  EXPECT_GT(linear[1], 0.8 * linear[0]) << linear[0] << " " << linear[1];
  EXPECT_GT(linear[1], 100 * quadratic[2]);
}

// A fluid with two independent structures: the tube's wall a soft ring model upstream and a
// second, four times stiffer one downstream (examples/tube/flow_two_walls). The inlet pressure
// rises linearly; linear acoustics (impedance rho c / A, c ~ sqrt(E)) gives the reflected share
// R = (c2 - c1) / (c2 + c1) = 1/3 and the transmitted T = 2 c2 / (c1 + c2) = 4/3 of the
// incident wave, here of its rate of rise (a slope does not care for the scheme's smearing of
// the front). Measured: R 0.326, T 1.339; the tube law's slight nonlinearity (500 Pa against
// rho c^2 = 30 kPa) and the discretisation allow 0.02.
TEST(SolverGroup, AWaveMeetsTheJunctionOfTwoWallsAsAcousticsSays) {
  const fs::path dir = copy_example("tube/flow_two_walls", "group_two_walls");
  const CommandResult run = run_cocopp("run -q " + (dir / "case.yaml").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto summary = read_json(dir / "results" / "case.summary.json");
  EXPECT_TRUE(summary["unconverged_steps"].empty()) << summary["unconverged_steps"];
  const auto pressure = read_dataset(dir / "results" / "case.h5", "y/wall/pressure");
  const std::size_t cells = 400, steps = pressure.size() / cells;
  ASSERT_EQ(steps, 500u);
  const double delta_t = 1e-4;
  // Least-squares slope of the pressure at `cell` over steps whose time is in [from, to] ms.
  auto slope = [&](std::size_t cell, double from, double to) {
    double n = 0, st = 0, sp = 0, stt = 0, stp = 0;
    for (std::size_t step = 1; step <= steps; ++step) {
      const double t = static_cast<double>(step) * delta_t, ms = 1e3 * t;
      if (ms < from - 1e-9 || ms > to + 1e-9) continue;
      const double p = pressure[(step - 1) * cells + cell];
      n += 1;
      st += t;
      sp += p;
      stt += t * t;
      stp += t * p;
    }
    return (n * stp - st * sp) / (n * stt - st * st);
  };
  // At z = -49.75 mm (cell 100) the incident front arrives at 9 ms and the reflected one at
  // 27 ms (the soft wall's wave speed 5.48 m/s), the inlet's reflection of it at 45 ms; at
  // z = +50.25 mm (cell 300) the transmitted front arrives at 23 ms.
  const double incident = slope(100, 13, 24);
  const double with_reflection = slope(100, 32, 44);
  const double transmitted = slope(300, 28, 50);
  EXPECT_NEAR(incident, 1e4, 100.0);  // Pa/s: the inlet's 100 Pa per 10 ms
  EXPECT_NEAR(with_reflection / incident - 1.0, 1.0 / 3.0, 0.02);
  EXPECT_NEAR(transmitted / incident, 4.0 / 3.0, 0.02);
  fs::remove_all(dir);
}

}  // namespace
