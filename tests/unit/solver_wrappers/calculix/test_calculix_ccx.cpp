// The calculix wrapper running ccx on structures with known answers: Lamé's thick-walled
// cylinder, the onset of yielding, the totals of the loads it writes, and ccx's own failures
// (the state reset is test_calculix_state_reset.cpp).
// Needs ccx (Debian package calculix-ccx); CMake builds this test only when ccx is found.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <vector>

#include "solver_wrappers/calculix/calculix_solver_wrapper.hpp"
#include "solver_wrappers/calculix/ccx_run.hpp"
#include "solver_wrappers/calculix/sta_file.hpp"
#include "solver_wrappers/process/child_process.hpp"
#include "tests/support/error_message.hpp"
#include "tests/unit/solver_wrappers/calculix/calculix_test_helpers.hpp"

using cocopp::testing::error_message;

namespace cocopp {
namespace {

using testing::CalculixCase;
using testing::dat_blocks;
using testing::kPi;
using testing::last_total_force;
using testing::SectorCylinder;

using testing::kDatPrecision;
using testing::kYield;
using testing::max_abs;
using testing::mode_keys;

/// What both modes must do alike: run per iteration (CalculixCcx/...) and persistent
/// (CoupledCcx/..., where cocopp-ccx is built).
class EveryMode : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryMode, ThickWalledCylinderMatchesLame) {
  CalculixCase test;
  SectorCylinder cylinder;
  test.start(cylinder.deck(), mode_keys(GetParam()));
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
}

/// Permanent radial displacement at the bore after loading to `p` and unloading, relative to
/// the displacement under `p`.
double permanent_set(double p, const std::string& mode) {
  CalculixCase test;
  SectorCylinder cylinder;
  cylinder.radial = 16;
  cylinder.grading = 4.0;
  cylinder.yield_stress = kYield;
  test.start(cylinder.deck(), mode_keys(mode));
  const double loaded = max_abs(test.radial(test.solve(p)));
  test.next_step();
  const double unloaded = max_abs(test.radial(test.solve(0.0)));
  return unloaded / loaded;
}

TEST_P(EveryMode, YieldingStartsAtTheAnalyticPressure) {
  SectorCylinder cylinder;
  cylinder.yield_stress = kYield;
  const double p_yield = cylinder.yield_onset_pressure();
  const double below = permanent_set(0.97 * p_yield, GetParam());
  const double above = permanent_set(1.03 * p_yield, GetParam());
  // Below: elastic, unloading returns to zero (to round-off); above: a permanent set (8e-4 of
  // the loaded displacement at 1.03 p_y with 16 graded elements).
  EXPECT_LT(below, 10 * kDatPrecision);
  EXPECT_GT(above, 1e-4);
}

TEST_P(EveryMode, LoadsOnASectorHaveTheAnalyticTotals) {
  CalculixCase test;
  SectorCylinder cylinder;
  cylinder.plane_strain = false;  // axially supported at the outer edge of z = 0 only
  cylinder.extra_step_cards =
      "*NODE PRINT, NSET=SUPPORT, TOTALS=ONLY, GLOBAL=YES\nRF\n"
      "*NODE PRINT, NSET=INNERN, GLOBAL=NO\nRF\n";
  test.start(cylinder.deck(), mode_keys(GetParam()));
  const double p = 10e6, tau = 3e6;
  test.solve(p, Eigen::Vector3d(0, 0, tau));
  const auto dat = test.printed_results();
  const double axial = tau * 2 * kPi * cylinder.ri * cylinder.length / 360.0;
  const double radial = p * 2 * kPi * cylinder.ri * cylinder.length / 360.0;
  // ccx's RF is each node's internal force: summed over the support, the axial reaction; at
  // the bore's nodes, in their cylindrical systems (ccx marks those values "L"), the radial
  // components are the applied radial forces (the reactions there are hoop forces only).
  EXPECT_NEAR(-last_total_force(dat, "SUPPORT").z(), axial, 1e-6 * axial);
  const auto bore = dat_blocks(dat, "forces", "INNERN");
  ASSERT_FALSE(bore.empty());
  double radial_total = 0.0;
  for (const auto& row : bore.rbegin()->second) radial_total += row.at(1);
  // The pressure's nodal forces are normal to the bore, radial to within the cosine of the
  // angle between a face's normal and a node's radius (at most 0.25 degree: 1e-5).
  EXPECT_NEAR(radial_total, radial, 2e-5 * radial);
}

// A traction equal to the pressure's force per area (p times the outward radial direction on
// the bore) must deform the sector like the pressure does: the nodal forces are rotated into
// the nodes' cylindrical *TRANSFORM systems (the sector lies at 45 degrees, where a missing
// rotation would put half of each force on the constrained hoop direction).
TEST_P(EveryMode, TractionIsRotatedIntoTheNodalSystems) {
  CalculixCase test;
  SectorCylinder cylinder;
  test.start(cylinder.deck(), mode_keys(GetParam()));
  const double p = 50e6;
  const Eigen::VectorXd by_pressure = test.radial(test.solve(p));
  Interface input = test.loads(0.0);
  const auto& faces = *input.parts().front().model_part;
  auto traction = input.values(faces.name, "traction");
  for (Eigen::Index f = 0; f < traction.rows(); ++f) {
    const Eigen::Vector3d centroid = faces.coordinates.row(f).transpose();
    traction.row(f) = p * Eigen::Vector3d(centroid.x(), centroid.y(), 0).normalized().transpose();
  }
  const Interface& output = test.wrapper().solve(input);
  const Eigen::VectorXd by_traction = test.radial(output.values(test.nodes().name, "displacement"));
  // Each face's traction direction is its centroid's: 0.25 degree off at its edges (6e-5).
  for (Eigen::Index i = 0; i < by_pressure.size(); ++i)
    EXPECT_NEAR(by_traction[i], by_pressure[i], 2e-4 * max_abs(by_pressure));
}

// Each face's total force (`input_variables: [force]`, what a conservative mapping of another
// solver's face forces gives) loads the sector as the pressure whose totals they are: the force
// radial at every node, the nodes' shares a uniform traction's.
TEST_P(EveryMode, FaceForcesLoadTheSectorAsTheirPressure) {
  SectorCylinder cylinder;
  CalculixCase by_pressure_case, by_force_case;
  by_pressure_case.start(cylinder.deck(), mode_keys(GetParam()));
  const double p = 50e6;
  const Eigen::VectorXd by_pressure = by_pressure_case.radial(by_pressure_case.solve(p));
  by_force_case.start(cylinder.deck(), mode_keys(GetParam()) + "input_variables: [force]\n");
  Interface input = by_force_case.wrapper().input_interface();
  const auto& faces = *input.parts().front().model_part;
  auto force = input.values(faces.name, "force");
  // The bore's faces are equal: each takes its share of p on the bore, radially outwards.
  const double share = p * cylinder.inner_area() / static_cast<double>(force.rows());
  for (Eigen::Index f = 0; f < force.rows(); ++f) {
    const Eigen::Vector3d centroid = faces.coordinates.row(f).transpose();
    force.row(f) = share * Eigen::Vector3d(centroid.x(), centroid.y(), 0).normalized().transpose();
  }
  const Interface& output = by_force_case.wrapper().solve(input);
  const Eigen::VectorXd by_force =
      by_force_case.radial(output.values(by_force_case.nodes().name, "displacement"));
  // Consistent nodal forces of the pressure and a uniform traction's shares of its total
  // differ by the faces' curvature across their 1 degree (measured 3.0e-6 of the displacement).
  for (Eigen::Index i = 0; i < by_pressure.size(); ++i)
    EXPECT_NEAR(by_force[i], by_pressure[i], 2e-5 * max_abs(by_pressure));
}

// The load totals on the axisymmetric model, whose loads stand for the whole ring: ccx takes a
// CAX model's *CLOAD per 360 degrees and prints the forces of the 2 degree wedge it expands
// the model into (times 180: the ring). On the model supported axially at one outer node, an
// axial shear traction tau on the bore gives the axial reaction tau 2 pi ri L, and an axial
// traction q on the end (an annulus, where the ring weight 2 pi r varies across each edge) the
// reaction q pi (ro^2 - ri^2), as ccx's own pressure q on that end does.
TEST_P(EveryMode, LoadsOnAnAxisymmetricModelHaveTheAnalyticTotals) {
  SectorCylinder cylinder;
  cylinder.element_type = "CAX8";
  cylinder.plane_strain = false;  // axially supported at the outer edge of y = 0 only
  cylinder.extra_step_cards = "*NODE PRINT, NSET=SUPPORT, TOTALS=ONLY\nRF\n";
  constexpr double kRingOverWedge = 180.0;
  const auto axial_reaction = [&](CalculixCase& test) {
    return -kRingOverWedge * last_total_force(test.printed_results(), "SUPPORT").y();
  };
  CalculixCase bore;
  bore.start(cylinder.deck(), mode_keys(GetParam()));
  const double tau = 3e6;
  bore.solve(0.0, Eigen::Vector3d(0, tau, 0));
  const double on_bore = tau * cylinder.inner_area();
  EXPECT_NEAR(axial_reaction(bore), on_bore, 1e-6 * on_bore);
  // Next step (restarted with the patched ccx): still axisymmetric, *CLOAD still per 360°.
  bore.next_step();
  bore.solve(0.0, Eigen::Vector3d(0, tau, 0));
  EXPECT_NEAR(axial_reaction(bore), on_bore, 1e-6 * on_bore) << "after a restart";

  CalculixCase end;
  end.start(cylinder.deck(), mode_keys(GetParam()), "TOP", "TOPN");
  const double q = 5e6;
  const double on_end = q * kPi * (cylinder.ro * cylinder.ro - cylinder.ri * cylinder.ri);
  end.solve(0.0, Eigen::Vector3d(0, -q, 0));
  EXPECT_NEAR(axial_reaction(end), -on_end, 1e-6 * on_end);
  end.solve(q);
  EXPECT_NEAR(axial_reaction(end), -on_end, 1e-6 * on_end);
}

// On the axisymmetric model a radial traction p e_r on the bore deforms it like the pressure p:
// the wrapper's ring weights (2 pi r) for the *CLOAD agree with ccx's own integration of the
// *DLOAD, to 2e-5 (measured 7.6e-6): ccx integrates the pressure over the flat faces of the
// 2 degree wedge it expands the model into (chords: 1 - sin(1°)/1° = 5e-5 short of the arc),
// not over the ring.
TEST_P(EveryMode, RadialTractionOnAnAxisymmetricModelActsLikeThePressure) {
  CalculixCase test;
  SectorCylinder cylinder;
  cylinder.element_type = "CAX8";
  test.start(cylinder.deck(), mode_keys(GetParam()));
  const double p = 50e6;
  const Eigen::VectorXd by_pressure = test.radial(test.solve(p));
  const Eigen::VectorXd by_traction = test.radial(test.solve(0.0, Eigen::Vector3d(p, 0, 0)));
  for (Eigen::Index i = 0; i < by_pressure.size(); ++i)
    EXPECT_NEAR(by_traction[i], by_pressure[i], 2e-5 * max_abs(by_pressure));
}

// Plane strain (CPE8, thickness 0.5): the strip compressed by a uniform pressure shortens by
// p Ly (1 - nu^2) / E, and the reactions equal pressure and shear traction times the loaded
// length times the thickness.
TEST_P(EveryMode, PlaneStrainStripHasTheAnalyticResponseAndTotals) {
  CalculixCase test;
  testing::PlaneStrainStrip strip;
  strip.extra_step_cards = "*NODE PRINT, NSET=BOTTOM, TOTALS=ONLY\nRF\n";
  test.start(strip.deck(), mode_keys(GetParam()), "TOP", "TOPN");
  const double p = 20e6, tau = 5e6;
  const RowMatrix u = test.solve(p);
  const double shortening = p * strip.ly * (1 - strip.poisson * strip.poisson) / strip.young;
  for (Eigen::Index i = 0; i < u.rows(); ++i) EXPECT_NEAR(u(i, 1), -shortening, 1e-6 * shortening);
  EXPECT_NEAR(last_total_force(test.printed_results(), "BOTTOM").y(),
              p * strip.lx * strip.thickness, 1e-6 * p * strip.lx * strip.thickness);
  test.solve(0.0, Eigen::Vector3d(tau, 0, 0));
  EXPECT_NEAR(-last_total_force(test.printed_results(), "BOTTOM").x(),
              tau * strip.lx * strip.thickness, 1e-6 * tau * strip.lx * strip.thickness);
}

std::string mode_name(const ::testing::TestParamInfo<std::string>& info) {
  return info.param == "persistent" ? "Persistent" : "PerIteration";
}

INSTANTIATE_TEST_SUITE_P(CalculixCcx, EveryMode, ::testing::Values("per_iteration"), mode_name);
#ifdef COCOPP_HAVE_COUPLED_CCX
INSTANTIATE_TEST_SUITE_P(CoupledCcx, EveryMode, ::testing::Values("persistent"), mode_name);
#endif

// *STATIC, SOLVER=SUITESPARSE (scripts/calculix/06-suitesparse-solver.patch, CHOLMOD for this
// symmetric matrix) must give SPOOLES's answer to round-off: the cylinder pressed past yield
// with NLGEOM, increments of Newton iterations, both solvers from the deck the wrapper
// copies. Persistent, the displacements come from memory: within 1e-10 of the largest
// (measured: 1.1e-18 m apart); per iteration, from the .dat file's digits (measured: the same
// digits), where the log also shows which solver factored (the persistent log is ccx's
// buffered output).
class SuiteSparse : public ::testing::TestWithParam<std::string> {};
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(SuiteSparse);

TEST_P(SuiteSparse, SolvesAsSpooles) {
  const bool persistent = GetParam() == "persistent";
  std::map<std::string, RowMatrix> u;
  for (const std::string solver : {"SPOOLES", "SUITESPARSE"}) {
    SCOPED_TRACE(solver);
    CalculixCase test;
    SectorCylinder cylinder;
    cylinder.yield_stress = kYield;
    cylinder.nlgeom = true;
    cylinder.procedure = "*STATIC, SOLVER=" + solver;
    test.start(cylinder.deck(), mode_keys(GetParam()));
    u[solver] = test.solve(1.6 * cylinder.yield_onset_pressure());
    if (!persistent) {
      const std::string log = testing::read_text(test.path("wall/wall.log"));
      EXPECT_CONTAINS(log, solver == "SPOOLES" ? "symmetric spooles solver"
                                               : "symmetric SuiteSparse (CHOLMOD) solver");
      EXPECT_EQ(log.find("unknown solver"), std::string::npos);
    }
  }
  const double largest = u["SPOOLES"].cwiseAbs().maxCoeff();
  ASSERT_GT(largest, 0.0);
  EXPECT_LE((u["SUITESPARSE"] - u["SPOOLES"]).cwiseAbs().maxCoeff(),
            (persistent ? 1e-10 : kDatPrecision) * largest);
}

#ifdef COCOPP_HAVE_PATCHED_CCX
INSTANTIATE_TEST_SUITE_P(CalculixCcx, SuiteSparse, ::testing::Values("per_iteration"), mode_name);
#endif
#ifdef COCOPP_HAVE_COUPLED_CCX
INSTANTIATE_TEST_SUITE_P(CoupledCcx, SuiteSparse, ::testing::Values("persistent"), mode_name);
#endif

TEST(CalculixCcx, DeckErrorQuotesCcx) {
  CalculixCase test;
  SectorCylinder cylinder;
  cylinder.extra_step_cards = "*BOUNDARY\nNOSUCHSET, 1, 1\n";
  test.start(cylinder.deck(), mode_keys("per_iteration"));
  const std::string message = testing::error_message<SolverError>([&] { test.solve(1e6); });
  EXPECT_CONTAINS(message, "ccx rejected the input deck at time step 1, coupling iteration 1");
  EXPECT_CONTAINS(message, "cocopp_iteration.inp (built from wall.inp)");
  EXPECT_CONTAINS(message, "*ERROR");
  EXPECT_CONTAINS(message, "NOSUCHSET");
}

// Non-convergence rejects the input (the coupled solver may step back): the wrapper keeps the
// step's start state and solves the step again for loads the cylinder can carry, as before.
/// Per iteration, and persistent: where cocopp-ccx ends, a new one replays the committed step.
class NonConvergence : public ::testing::TestWithParam<std::string> {};

TEST_P(NonConvergence, RejectsTheInputAndKeepsTheStepStart) {
  CalculixCase test;
  SectorCylinder cylinder;
  cylinder.yield_stress = kYield;
  test.start(cylinder.deck(), mode_keys(GetParam()));
  test.solve(0.5 * cylinder.yield_onset_pressure());
  test.wrapper().finalize_step();
  test.wrapper().initialize_step(2, 2.0);
  const RowMatrix before = test.solve(0.6 * cylinder.yield_onset_pressure());
  // Twice the yield stress is beyond the collapse pressure (2 / sqrt(3) ln(ro / ri) sigma_y).
  const std::string message =
      testing::error_message<SolverRejectedInput>([&] { test.solve(2 * kYield); });
  EXPECT_CONTAINS(message, "ccx did not converge at time step 2, coupling iteration 2");
  EXPECT_CONTAINS(message,
                  GetParam() == "persistent" ? "cocopp-ccx exited" : "exited with code 201");
  EXPECT_CONTAINS(message, "increment size smaller than minimum");
  EXPECT_CONTAINS(message, "what to change: a smaller time step (settings.delta_t)");
  const RowMatrix after = test.solve(0.6 * cylinder.yield_onset_pressure());
  EXPECT_LT((after - before).cwiseAbs().maxCoeff(), 1e-9 * before.cwiseAbs().maxCoeff());
}

INSTANTIATE_TEST_SUITE_P(CalculixCcx, NonConvergence, ::testing::Values("per_iteration"),
                         mode_name);
#ifdef COCOPP_HAVE_COUPLED_CCX
INSTANTIATE_TEST_SUITE_P(CoupledCcx, NonConvergence, ::testing::Values("persistent"), mode_name);
#endif

/// The .sta attempts and the *STATIC data line of the wrapper's last ccx run.
struct LastRun {
  std::vector<calculix::IncrementAttempt> attempts;
  std::string static_line;
  int newton_iterations() const {
    int total = 0;
    for (const auto& attempt : attempts) total += attempt.newton_iterations;
    return total;
  }
};

LastRun last_run(const CalculixCase& test) {
  LastRun run{calculix::read_sta(test.path("wall/cocopp_iteration.sta")), {}};
  std::ifstream deck(test.path("wall/cocopp_iteration.inp"));
  std::string line;
  while (std::getline(deck, line))
    if (line == "*STATIC") std::getline(deck, run.static_line);
  return run;
}

// The cylinder pressed in one full increment to 1.6 times its yield onset, with ccx allowed 3
// Newton iterations an increment (*CONTROLS): the full increment needs 4, so ccx cuts it back
// ("1U") and goes on in halves. With initial_increment: previous_iteration the step's
// second coupling iteration starts at the increment that converged: no failed attempt, fewer
// Newton iterations, the same increments and so the same displacements; the next time step
// tries the deck's increment again. Without the key every iteration repeats the failure.
TEST(CalculixCcx, CarriedInitialIncrementSkipsTheCutBack) {
  SectorCylinder cylinder;
  cylinder.yield_stress = kYield;
  cylinder.nlgeom = true;
  cylinder.increments = "1e-4, 1e-4";  // the wire drawing case's time step
  cylinder.extra_step_cards =
      "*CONTROLS, PARAMETERS=TIME INCREMENTATION\n3, 3, 9, 3, 10, 4, 0, 5\n";
  const double p = 1.6 * cylinder.yield_onset_pressure();
  for (const bool carry : {false, true}) {
    SCOPED_TRACE(carry ? "carried" : "the deck's");
    CalculixCase test(1e-4);
    test.start(cylinder.deck(),
               carry ? "initial_increment: previous_iteration\n" : mode_keys("per_iteration"));
    const RowMatrix first = test.solve(p);
    const LastRun first_run = last_run(test);
    ASSERT_FALSE(first_run.attempts.empty());
    ASSERT_FALSE(first_run.attempts.front().converged) << "the full increment should fail";
    EXPECT_EQ(first_run.static_line, "1e-4, 1e-4");

    const RowMatrix second = test.solve(p);
    const LastRun second_run = last_run(test);
    EXPECT_LE((second - first).cwiseAbs().maxCoeff(), kDatPrecision * first.cwiseAbs().maxCoeff());
    if (!carry) {
      EXPECT_FALSE(second_run.attempts.front().converged);
      EXPECT_EQ(second_run.newton_iterations(), first_run.newton_iterations());
      continue;
    }
    const double carried = *calculix::first_converged_increment(first_run.attempts);
    EXPECT_LT(carried, 1e-4);
    EXPECT_DOUBLE_EQ(std::stod(second_run.static_line), carried);
    // In ccx's 20 characters (5e-05 has no short binary form: "5.0000000000000002e-05").
    EXPECT_LE(second_run.static_line.find(','), 20U);
    EXPECT_EQ(second_run.static_line.substr(second_run.static_line.find(',')), ", 1e-4");
    for (const auto& attempt : second_run.attempts) EXPECT_TRUE(attempt.converged);
    EXPECT_LT(second_run.newton_iterations(), first_run.newton_iterations());

    test.wrapper().finalize_step();
    test.wrapper().initialize_step(2, 2e-4);
    test.solve(p);
    EXPECT_EQ(last_run(test).static_line, "1e-4, 1e-4");
  }
}

#ifdef COCOPP_HAVE_PATCHED_CCX
// warm_start: the step's next coupling iterations start ccx's Newton iterations from the last
// one's solution (07-warm-start.patch): the cylinder yielding under NLGEOM in one increment, a
// second and a third iteration with loads changed by 1e-5 (a coupling near its fixed point).
// A cold start stops at ccx's default tolerance 1.5e-4 of the displacement short of the answer
// ccx converges to far below it (*CONTROLS, PARAMETERS=FIELD 1e-10, 1e-10); a warm start, its
// corrections measured against how far the increment moved, converges in its first Newton
// iteration to within 1.5e-6 (measured; the bound is 1/20 of the cold start's miss). The
// next time step starts cold (the last step's increments are no guess for it).
TEST(CalculixCcx, WarmStartTakesFewerNewtonIterationsToTheConvergedAnswer) {
  enum Start { kCold, kWarm, kTight };
  SectorCylinder plastic;
  plastic.yield_stress = kYield;
  const double p = 1.5 * plastic.yield_onset_pressure();
  const std::vector<double> loads = {p, p * (1 + 1e-5), p * (1 - 1e-5)};
  std::map<Start, std::vector<RowMatrix>> answers;
  std::map<Start, std::vector<int>> newton;
  std::map<Start, int> next_step_newton;
  for (const Start start : {kCold, kWarm, kTight}) {
    SCOPED_TRACE(start == kCold ? "cold" : start == kWarm ? "warm" : "tight");
    SectorCylinder cylinder;
    cylinder.yield_stress = kYield;
    cylinder.nlgeom = true;
    cylinder.increments = "1.0, 1.0";  // one increment, as the wire drawing case's held steps
    if (start == kTight) cylinder.extra_step_cards = "*CONTROLS, PARAMETERS=FIELD\n1e-10, 1e-10\n";
    CalculixCase test;
    test.start(cylinder.deck(), start == kWarm ? "warm_start: true\n" : mode_keys("per_iteration"));
    for (const double load : loads) {
      answers[start].push_back(test.solve(load));
      newton[start].push_back(last_run(test).newton_iterations());
    }
    const std::string log = testing::read_text(test.path("wall/wall.log"));
    EXPECT_EQ(log.find("starts from the previous coupling iteration") != std::string::npos,
              start == kWarm);
    test.next_step();
    test.solve(p);
    next_step_newton[start] = last_run(test).newton_iterations();
  }
  EXPECT_EQ(next_step_newton[kWarm], next_step_newton[kCold]) << "a new step starts cold";
  EXPECT_EQ(newton[kWarm][0], newton[kCold][0]);  // the first iteration has no guess
  for (std::size_t i = 0; i < loads.size(); ++i) {
    SCOPED_TRACE("iteration " + std::to_string(i + 1));
    const RowMatrix& converged = answers[kTight][i];
    const double largest = converged.cwiseAbs().maxCoeff();
    const double warm_error = (answers[kWarm][i] - converged).cwiseAbs().maxCoeff();
    const double cold_error = (answers[kCold][i] - converged).cwiseAbs().maxCoeff();
    std::cout << "iteration " << i + 1 << ": Newton iterations cold " << newton[kCold][i]
              << ", warm " << newton[kWarm][i] << "; off the converged answer cold "
              << cold_error / largest << ", warm " << warm_error / largest << " of the largest\n";
    if (i == 0) continue;
    EXPECT_LT(newton[kWarm][i], newton[kCold][i]);
    EXPECT_LE(warm_error, cold_error / 20);
  }
}
#endif

// warm_start needs a ccx that records and reads guesses, and one ccx run per time step.
TEST(CalculixCcx, WarmStartRefusesWhatCannotTakeIt) {
  SectorCylinder cylinder;
  {
    CalculixCase test;
    const std::string message = error_message<CaseError>(
        [&] { test.start(cylinder.deck(), "warm_start: true\nstate_reset: replay\n"); });
    EXPECT_CONTAINS(message, "case.yaml:");
    EXPECT_CONTAINS(message, "state_reset: restart");
  }
  if (std::filesystem::exists("/usr/bin/ccx")) {
    CalculixCase test;
    const std::string message = error_message<CaseError>(
        [&] { test.start(cylinder.deck(), "warm_start: true\nexecutable: /usr/bin/ccx\n"); });
    EXPECT_CONTAINS(message, "07-warm-start.patch");
  }
}

/// How many times `text` starts a line of `file`.
int lines_starting_with(const std::filesystem::path& file, const std::string& text) {
  std::ifstream in(file);
  int count = 0;
  for (std::string line; std::getline(in, line);) count += line.rfind(text, 0) == 0 ? 1 : 0;
  return count;
}

// A coupling iteration's results are read at its step's end: the deck's output cards write only
// the step's last increment (ccx always writes it), not each of the step's 4 here, and the
// answer is Lamé's as ever. A deck that sets an output FREQUENCY keeps its own.
TEST(CalculixCcx, AnIterationWritesOnlyItsStepsEnd) {
  for (const bool deck_frequency : {false, true}) {
    SCOPED_TRACE(deck_frequency ? "the deck's FREQUENCY=2" : "no FREQUENCY in the deck");
    SectorCylinder cylinder;
    cylinder.nlgeom = true;
    cylinder.procedure = "*STATIC, DIRECT";  // four increments of a quarter
    cylinder.increments = "0.25, 1.0";
    cylinder.extra_step_cards = deck_frequency ? "*NODE FILE, FREQUENCY=2\nU\n" : "*NODE FILE\nU\n";
    CalculixCase test;
    test.start(cylinder.deck(), mode_keys("per_iteration"));
    const double p = 100e6;
    const Eigen::VectorXd radial = test.radial(test.solve(p));
    const double expected = cylinder.lame_radial_displacement(p, cylinder.ri);
    // The full load's (NLGEOM leaves 4e-4 from small-strain Lamé), not an earlier quarter's.
    for (Eigen::Index i = 0; i < radial.size(); ++i)
      EXPECT_NEAR(radial[i], expected, 1e-3 * expected);
    EXPECT_EQ(calculix::read_sta(test.path("wall/cocopp_iteration.sta")).size(), 4U);
    EXPECT_EQ(lines_starting_with(test.path("wall/cocopp_iteration.frd"), " -4  DISP"),
              deck_frequency ? 2 : 1);
    // ccx's prints follow the deck's file FREQUENCY too: increments 2 and 4.
    EXPECT_EQ(lines_starting_with(test.path("wall/cocopp_iteration.dat"), " displacements"),
              deck_frequency ? 2 : 1);
  }
}

#ifdef COCOPP_HAVE_PATCHED_CCX
/// The Newton iterations of every increment in a .sta file ("STEP INC ATT ITRS ...").
std::vector<int> newton_iterations(const std::filesystem::path& sta_file) {
  std::vector<int> iterations;
  for (const auto& attempt : calculix::read_sta(sta_file))
    iterations.push_back(attempt.newton_iterations);
  return iterations;
}

/// Runs `deck` as <directory>/<job>.inp with `executable`; its .dat and .sta files.
void run_deck(const std::filesystem::path& executable, const std::filesystem::path& directory,
              const std::string& deck) {
  std::filesystem::create_directories(directory);
  testing::write_text(directory / "job.inp", deck);
  const auto result =
      calculix::run_ccx({executable, directory, "job", directory / "job.log", 2, 600.0});
  ASSERT_EQ(result.status, calculix::CcxRunResult::Status::kSuccess) << result.details;
}

// 04-nonlinear-anisotropic-stiffness.patch assembles the NLGEOM stiffness of a plastic solid
// (ccx's anisotropic tangent) from coefficients taken once per integration point. The
// cylinder pressed well past yield (1.6 times the onset pressure), with full and reduced
// integration, takes the same Newton iterations in every increment as with Debian's ccx and
// ends at the same displacements to the printed digits (the sums differ in order only). A
// wrong coefficient shows in both: a tangent off by a little costs Newton iterations.
TEST(PatchedCcx, PlasticNlgeomStiffnessIsDebiansToRoundOff) {
  if (!std::filesystem::exists("/usr/bin/ccx")) GTEST_SKIP() << "no Debian ccx in /usr/bin";
  testing::TemporaryDirectory directory;
  for (const std::string element_type : {"C3D20", "C3D20R"}) {
    SCOPED_TRACE(element_type);
    SectorCylinder cylinder;
    cylinder.element_type = element_type;
    cylinder.yield_stress = kYield;
    cylinder.nlgeom = true;
    cylinder.increments = "0.1, 1.0";
    // Collapse (2 / sqrt(3) ln(ro / ri) sigma_y) is at 1.85 times the onset.
    const double pressure = 1.6 * cylinder.yield_onset_pressure();
    cylinder.extra_step_cards = "*DLOAD\nINNER, P, " + std::to_string(pressure) +
                                "\n*NODE PRINT, NSET=NALL\nU\n*EL PRINT, ELSET=EALL\nPEEQ\n";
    const std::string deck = cylinder.deck();
    const auto patched = directory / (element_type + "-patched");
    const auto debian = directory / (element_type + "-debian");
    run_deck(COCOPP_PATCHED_CCX, patched, deck);
    run_deck("/usr/bin/ccx", debian, deck);

    const std::vector<int> iterations = newton_iterations(patched / "job.sta");
    EXPECT_GE(iterations.size(), 5U);
    EXPECT_EQ(iterations, newton_iterations(debian / "job.sta"));
    const auto u_patched = dat_blocks(patched / "job.dat", "displacements", "NALL");
    const auto u_debian = dat_blocks(debian / "job.dat", "displacements", "NALL");
    ASSERT_EQ(u_patched.size(), iterations.size());
    ASSERT_EQ(u_debian.size(), u_patched.size());
    for (auto a = u_patched.begin(), b = u_debian.begin(); a != u_patched.end(); ++a, ++b) {
      ASSERT_EQ(a->second.size(), b->second.size());
      double largest = 0.0, difference = 0.0;
      for (std::size_t n = 0; n < a->second.size(); ++n)
        for (std::size_t c = 1; c < 4; ++c) {
          largest = std::max(largest, std::abs(a->second[n].at(c)));
          difference = std::max(difference, std::abs(a->second[n].at(c) - b->second[n].at(c)));
        }
      EXPECT_LE(difference, kDatPrecision * largest) << "at time " << a->first;
    }
    // Plastic in the inner part of the wall (90 of 216 integration points with C3D20, 28 of 32
    // with C3D20R): the anisotropic tangent is what was assembled there.
    const auto peeq = dat_blocks(patched / "job.dat", "equivalent plastic strain", "EALL");
    ASSERT_FALSE(peeq.empty());
    int plastic_points = 0, points = 0;
    for (const auto& row : peeq.rbegin()->second) {
      ++points;
      if (row.at(2) > 0.0) ++plastic_points;
    }
    EXPECT_GT(plastic_points, points / 3);
  }
}
#endif

#ifdef COCOPP_HAVE_COUPLED_CCX
// mode: persistent refuses, by key, what only the per-iteration mode does.
TEST(CoupledCcx, RefusesWhatOnlyPerIterationModeDoes) {
  SectorCylinder cylinder;
  for (const std::string keys : {"state_reset: replay\n", "initial_increment: previous_iteration\n",
                                 "interface_drive: displacement\nsurface_stiffness: 1e15\n"}) {
    CalculixCase test;
    const std::string message = error_message<CaseError>(
        [&] { test.create(cylinder.deck(), "mode: persistent\n" + keys); });
    EXPECT_CONTAINS(message, "case.yaml:");
    EXPECT_CONTAINS(message, keys.substr(0, keys.find(':')));
    EXPECT_CONTAINS(message, "mode: per_iteration");
  }
}

// A deck error that ccx finds stops the start, in ccx's own words.
TEST(CoupledCcx, DeckErrorQuotesCcx) {
  CalculixCase test;
  SectorCylinder cylinder;
  cylinder.extra_step_cards = "*BOUNDARY\nNOSUCHSET, 1, 1\n";
  test.create(cylinder.deck(), "mode: persistent\n");
  const std::string message = error_message<SolverError>([&] { test.wrapper().initialize(); });
  EXPECT_CONTAINS(message, "solver 'wall'");
  EXPECT_CONTAINS(message, "*ERROR");
  EXPECT_CONTAINS(message, "NOSUCHSET");
}
#endif

}  // namespace
}  // namespace cocopp
