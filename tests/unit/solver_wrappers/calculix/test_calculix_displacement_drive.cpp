// The calculix wrapper with `interface_drive: displacement` (displacement_drive.hpp) on Lamé's
// thick-walled cylinder (a 1-degree sector, plane strain), whose bore under a pressure p moves
// radially by u* (the ccx solution agrees with Lamé to 1e-4, test_calculix_ccx.cpp):
// - driven at u*, the wrapper returns u*: ccx's reactions balance the pressure there;
// - driven at 2 u*, with the bore's true stiffness per area (p / u*), one Newton step lands on
//   u*: the imbalance's sign, size and units are right;
// - nodes leave the driven set from one step to the next (the sliding interface).
// Needs ccx (Debian package calculix-ccx); CMake builds this test only when ccx is found.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <functional>

#include "solver_wrappers/calculix/calculix_solver_wrapper.hpp"
#include "tests/support/calculix_models.hpp"
#include "tests/support/error_message.hpp"
#include "tests/unit/solver_wrappers/calculix/calculix_test_helpers.hpp"

namespace cocopp {
namespace {

using testing::CalculixCase;
using testing::error_message;
using testing::max_abs;
using testing::SectorCylinder;

constexpr double kPressure = 100e6;

SectorCylinder cylinder() {
  SectorCylinder model;
  model.axial = 4;  // four faces on the bore, so that some nodes are shared
  return model;
}

double bore_displacement() {
  const SectorCylinder model = cylinder();
  return model.lame_radial_displacement(kPressure, model.ri);
}

/// The settings of the displacement drive with the bore's stiffness per area times `factor`.
std::string drive_keys(double factor = 1.0) {
  return fmt::format("interface_drive: displacement\nsurface_stiffness: {}\n",
                     factor * kPressure / bore_displacement());
}

/// The wrapper's input: the pressure on every face, the wall at `radial` (outward from the
/// axis) at every drivable node, the faces `covered` says covered, and a thick film (its
/// stiffness 2 p / gap is negligible).
Interface drive_inputs(CalculixCase& test, double radial,
                       const std::function<bool(Eigen::Index)>& covered) {
  Interface input = test.loads(kPressure);
  const auto& nodes = *input.parts().front().model_part;
  const auto& faces = *input.parts().back().model_part;
  auto wall = input.values(nodes.name, "wall_displacement");
  for (Eigen::Index n = 0; n < nodes.coordinates.rows(); ++n)
    wall.row(n) =
        radial *
        Eigen::RowVector3d(nodes.coordinates(n, 0), nodes.coordinates(n, 1), 0.0).normalized();
  auto coverage = input.values(faces.name, "coverage");
  input.values(faces.name, "gap").setConstant(1.0);
  for (Eigen::Index f = 0; f < faces.coordinates.rows(); ++f)
    coverage(f, 0) = covered(f) ? 1.0 : 0.0;
  return input;
}

Eigen::VectorXd solve_radial(CalculixCase& test, const Interface& input) {
  const Interface& output = test.wrapper().solve(input);
  return test.radial(output.values(test.nodes().name, "displacement"));
}

const auto kEveryFace = [](Eigen::Index) { return true; };
const auto kFirstTwoFaces = [](Eigen::Index face) { return face < 2; };

TEST(CalculixDisplacementDrive, DrivenAtTheLoadedSolutionStaysThere) {
  CalculixCase test;
  test.start(cylinder().deck(), drive_keys());
  const double u = bore_displacement();
  const Eigen::VectorXd radial = solve_radial(test, drive_inputs(test, u, kEveryFace));
  for (Eigen::Index i = 0; i < radial.size(); ++i)
    EXPECT_NEAR(radial[i], u, 2e-4 * u) << "node " << test.nodes().ids[i];
}

TEST(CalculixDisplacementDrive, OneNewtonStepWithTheTrueStiffnessLandsOnTheSolution) {
  CalculixCase test;
  test.start(cylinder().deck(), drive_keys());
  const double u = bore_displacement();
  // Driven twice as far, the bore takes twice the pressure: the imbalance is -p, and p over
  // the stiffness p / u* is the step back to u*.
  const Eigen::VectorXd radial = solve_radial(test, drive_inputs(test, 2 * u, kEveryFace));
  for (Eigen::Index i = 0; i < radial.size(); ++i)
    EXPECT_NEAR(radial[i], u, 2e-4 * u) << "node " << test.nodes().ids[i];
  // With a stiffness estimate twice too high the step goes halfway: the update contracts.
  CalculixCase stiff;
  stiff.start(cylinder().deck(), drive_keys(2.0));
  const Eigen::VectorXd halfway = solve_radial(stiff, drive_inputs(stiff, 2 * u, kEveryFace));
  for (Eigen::Index i = 0; i < halfway.size(); ++i)
    EXPECT_NEAR(halfway[i], 1.5 * u, 3e-4 * u) << "node " << stiff.nodes().ids[i];
}

// A sector whose interface node set is one side of the bore only (as an axisymmetric mapping
// wants it): with driven_node_set the whole bore is driven, and the side is returned.
TEST(CalculixDisplacementDrive, DrivesTheWholeSurfaceAndReturnsOneSide) {
  const SectorCylinder model = cylinder();
  std::string side = "*NSET, NSET=SIDE\n";
  const int ni = 2 * model.radial + 1;
  for (int k = 0; k <= 2 * model.axial; ++k) side += std::to_string(1 + 3 * ni * k) + ",\n";
  std::string deck = model.deck();
  deck.insert(deck.find("*MATERIAL"), side);
  CalculixCase test;
  test.start(deck, drive_keys() + "driven_node_set: INNERN\n", "INNER", "SIDE");
  EXPECT_EQ(test.nodes().ids.size(), static_cast<std::size_t>(2 * model.axial + 1));
  const double u = bore_displacement();
  const Eigen::VectorXd radial = solve_radial(test, drive_inputs(test, 2 * u, kEveryFace));
  for (Eigen::Index i = 0; i < radial.size(); ++i)
    EXPECT_NEAR(radial[i], u, 2e-4 * u) << "node " << test.nodes().ids[i];
}

TEST(CalculixDisplacementDrive, PartlyCoveredSurfaceIsDrivenWhereCoveredAndLoadedElsewhere) {
  CalculixCase test;
  test.start(cylinder().deck(), drive_keys());
  const double u = bore_displacement();
  // The first two faces covered: their nodes are driven at u*, except the corner shared with
  // the third face; the rest is loaded by the pressure alone. Both give u*, to 4e-4 where they
  // meet: C3D20R's solution under the pressure is not quite uniform around the hoop (the
  // reactions of the uniformly driven bore show a hoop zigzag of 2-5 % that cancels on every
  // face), and the faces next to the free nodes do not cancel it entirely.
  const Eigen::VectorXd radial =
      solve_radial(test, drive_inputs(test, u, [](Eigen::Index f) { return f < 2; }));
  for (Eigen::Index i = 0; i < radial.size(); ++i)
    EXPECT_NEAR(radial[i], u, 5e-4 * u) << "node " << test.nodes().ids[i];
}

TEST(CalculixDisplacementDrive, NodesLeaveTheDrivenSetInTheNextStep) {
  CalculixCase test;
  test.start(cylinder().deck(), drive_keys(1e6));  // stiff: the bore stays near 2 u*
  const double u = bore_displacement();
  const Eigen::VectorXd driven = solve_radial(test, drive_inputs(test, 2 * u, kEveryFace));
  EXPECT_NEAR(max_abs(driven), 2 * u, 1e-3 * u);
  test.wrapper().finalize_step();
  test.wrapper().initialize_step(2, 2.0);
  // Nothing covered: every node is released (ccx keeps a prescribed node otherwise) and the
  // pressure alone gives u*; the deck's plane strain still holds (its *BOUNDARY again).
  const Interface& output =
      test.wrapper().solve(drive_inputs(test, 2 * u, [](Eigen::Index) { return false; }));
  const RowMatrix displacement = output.values(test.nodes().name, "displacement");
  const Eigen::VectorXd radial = test.radial(displacement);
  for (Eigen::Index i = 0; i < radial.size(); ++i)
    EXPECT_NEAR(radial[i], u, 2e-4 * u) << "node " << test.nodes().ids[i];
  EXPECT_LT(displacement.col(2).cwiseAbs().maxCoeff(), 1e-6 * u);
}

// NLGEOM: the loads act on the faces where the wall puts them, both sides of the sector moved
// from the last converged step (the loaded nodes of the uncovered face stay there). A run
// restarted after step 2 takes them from the restart data and continues as the uninterrupted
// run (to the .dat file's 7 digits, which the faces are read with).
TEST(CalculixDisplacementDrive, ARestartedDrivenRunContinuesAsTheUninterruptedOne) {
  SectorCylinder model = cylinder();
  model.nlgeom = true;
  const double u = bore_displacement();
  const std::vector<double> walls = {1.5 * u, 0.5 * u, 1.2 * u};
  CalculixCase test;
  test.create(model.deck(), drive_keys() + "mode: per_iteration\n");
  test.wrapper().initialize();
  Eigen::VectorXd uninterrupted;
  for (int n = 1; n <= 3; ++n) {
    test.wrapper().initialize_step(n, n);
    uninterrupted = solve_radial(test, drive_inputs(test, walls[n - 1], kFirstTwoFaces));
    test.wrapper().finalize_step();
    if (n == 2) test.wrapper().save_restart(2);
  }
  test.wrapper().finalize();
  test.run().timestep_start = 2;
  test.create(model.deck(), drive_keys() + "mode: per_iteration\n");
  test.wrapper().initialize();
  test.wrapper().initialize_step(3, 3);
  const Eigen::VectorXd restarted =
      solve_radial(test, drive_inputs(test, walls[2], kFirstTwoFaces));
  EXPECT_LE(max_abs(restarted - uninterrupted), 1e-6 * max_abs(uninterrupted));
  EXPECT_GT(max_abs(restarted), 0.3 * u);
}

TEST(CalculixDisplacementDrive, RefusesAnAxisymmetricModel) {
  CalculixCase test;
  SectorCylinder model = cylinder();
  model.element_type = "CAX8";
  const std::string message =
      error_message<CaseError>([&] { test.start(model.deck(), drive_keys()); });
  EXPECT_CONTAINS(message, "CAX8");
  EXPECT_CONTAINS(message, "reaction_probe.py");
  EXPECT_CONTAINS(message, "3D sector");
}

TEST(CalculixDisplacementDrive, RefusesABoundaryInsideTheStep) {
  CalculixCase test;
  SectorCylinder model = cylinder();
  model.extra_step_cards = "*BOUNDARY\nSUPPORT, 1, 1\n";
  const std::string message =
      error_message<CaseError>([&] { test.start(model.deck(), drive_keys()); });
  EXPECT_CONTAINS(message, "wall.inp:");
  EXPECT_CONTAINS(message, "move it before *STEP");
}

TEST(CalculixDisplacementDrive, NeedsTheSurfaceStiffness) {
  CalculixCase test;
  EXPECT_CONTAINS(error_message<CaseError>(
                      [&] { test.create(cylinder().deck(), "interface_drive: displacement\n"); }),
                  "surface_stiffness");
}

}  // namespace
}  // namespace cocopp
