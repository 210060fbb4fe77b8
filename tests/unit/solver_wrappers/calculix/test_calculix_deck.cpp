// The CalculiX wrapper's parts that need no ccx: reading decks, face geometry, the loads file,
// the .dat reader, ccx's error messages, and the wrapper's errors when ccx is missing, crashes
// or hangs (a stand-in script plays ccx).
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <cstdlib>

#include "solver_wrappers/calculix/ccx_run.hpp"
#include "solver_wrappers/calculix/dat_file.hpp"
#include "solver_wrappers/calculix/element_faces.hpp"
#include "solver_wrappers/calculix/input_deck.hpp"
#include "solver_wrappers/calculix/interface_loads.hpp"
#include "solver_wrappers/calculix/sta_file.hpp"
#include "tests/support/error_message.hpp"
#include "tests/unit/solver_wrappers/calculix/calculix_test_helpers.hpp"

using cocopp::testing::error_message;

namespace cocopp {
namespace {

using calculix::DeckError;
using calculix::InputDeck;
using testing::CalculixCase;
using testing::kPi;
using testing::read_text;
using testing::SectorCylinder;
using testing::TemporaryDirectory;
using testing::write_text;

/// Two C3D20 elements side by side (x in [0, 2], y, z in [0, 1]) from a generated sector-free
/// layout: nodes on a 5 x 3 x 3 grid of half-element spacing.
std::string two_hexes(const std::string& extra = "") {
  std::string deck = "*NODE, NSET=NALL\n";
  const auto id = [](int i, int j, int k) { return 1 + i + 5 * (j + 3 * k); };
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 5; ++i)
        if ((i % 2) + (j % 2) + (k % 2) <= 1)
          deck += std::to_string(id(i, j, k)) + ", " + std::to_string(i * 0.5) + ", " +
                  std::to_string(j * 0.5) + ", " + std::to_string(k * 0.5) + "\n";
  static const int local[20][3] = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, {0, 0, 2},
                                   {2, 0, 2}, {2, 2, 2}, {0, 2, 2}, {1, 0, 0}, {2, 1, 0},
                                   {1, 2, 0}, {0, 1, 0}, {1, 0, 2}, {2, 1, 2}, {1, 2, 2},
                                   {0, 1, 2}, {0, 0, 1}, {2, 0, 1}, {2, 2, 1}, {0, 2, 1}};
  deck += "*ELEMENT, TYPE=C3D20R, ELSET=EALL\n";
  for (int e = 0; e < 2; ++e) {
    deck += std::to_string(e + 1);
    for (int n = 0; n < 20; ++n)
      deck += (n == 15 ? ",\n" : ", ") +
              std::to_string(id(2 * e + local[n][0], local[n][1], local[n][2]));
    deck += "\n";
  }
  return deck + extra;
}

const std::string kStep = "*STEP\n*STATIC\n0.5, 2.0\n*END STEP\n";

class DeckTest : public ::testing::Test {
 protected:
  InputDeck read(const std::string& text) {
    write_text(directory_ / "deck.inp", text);
    return InputDeck::read(directory_ / "deck.inp", directory_.path());
  }
  TemporaryDirectory directory_;
};

TEST_F(DeckTest, ReadsMeshSetsSurfacesIncludesAndTheStep) {
  write_text(directory_ / "mesh.inp", two_hexes());
  const InputDeck deck = read(
      "** a comment\n*INCLUDE, INPUT=mesh.inp\n*NSET, NSET=FEW, GENERATE\n1, 5, 2\n"
      "*NSET, NSET=MORE\nFEW, 15\n*ELSET, ELSET=SECOND\n2\n"
      "*SURFACE, NAME=TOP, TYPE=ELEMENT\n1, S3\nSECOND, S3\n" +
      kStep);
  EXPECT_EQ(deck.nodes().size(), 32u);  // 45 grid points less the 13 with 2+ odd indices
  ASSERT_EQ(deck.elements().size(), 2u);
  EXPECT_EQ(deck.element(2).type, "C3D20R");
  EXPECT_EQ(deck.element(2).nodes.size(), 20u);
  EXPECT_EQ(deck.node_set("more"), (std::vector<std::int64_t>{1, 3, 5, 15}));
  ASSERT_EQ(deck.surface("Top").size(), 2u);
  EXPECT_EQ(deck.surface("TOP")[1].element, 2);
  EXPECT_EQ(deck.surface("TOP")[1].face, 3);
  EXPECT_EQ(deck.procedure(), "STATIC");
  EXPECT_DOUBLE_EQ(deck.step_time_period(), 2.0);
  EXPECT_DOUBLE_EQ(deck.initial_increment(), 0.5);
  ASSERT_TRUE(deck.procedure_data_line());
  EXPECT_EQ(deck.step().at(*deck.procedure_data_line()).text, "0.5, 2.0");
  EXPECT_EQ(deck.step().front().text, "*STEP");
  EXPECT_EQ(deck.step().back().text, "*END STEP");
  EXPECT_TRUE(deck.has_keyword("ELEMENT"));
  EXPECT_FALSE(deck.has_keyword("PLASTIC"));
}

TEST_F(DeckTest, ErrorsNameTheFileAndLine) {
  EXPECT_CONTAINS(error_message<DeckError>([&] { read(two_hexes() + kStep + kStep); }),
                  "a second *STEP");
  EXPECT_CONTAINS(error_message<DeckError>([&] { read(two_hexes() + "*RESTART, READ\n" + kStep); }),
                  "*RESTART: the calculix wrapper writes and reads the restart files");
  EXPECT_CONTAINS(error_message<DeckError>([&] { read("*INCLUDE, INPUT=missing.inp\n" + kStep); }),
                  "deck.inp:1: cannot read");
  EXPECT_CONTAINS(
      error_message<DeckError>([&] { read(two_hexes("*NSET, NSET=A\nNOSUCH\n") + kStep); }),
      "deck.inp:40: *NSET: set NOSUCH is not defined");
  EXPECT_CONTAINS(error_message<DeckError>([&] { read(two_hexes()); }), "no *STEP");
  EXPECT_CONTAINS(error_message<DeckError>([&] { read("*NODE\n1, 0, zero, 0\n" + kStep); }),
                  "deck.inp:2: 'zero' is not a number");
  EXPECT_CONTAINS(
      error_message<DeckError>([&] { read("*ELEMENT, TYPE=C3D8\n1, 1, 2, 3\n" + kStep); }),
      "has 3 nodes (8 expected)");
  // Found by the deck fuzz target: an *END STEP before any *STEP read an empty step (SEGV).
  EXPECT_CONTAINS(error_message<DeckError>([&] { read(two_hexes() + "*END STEP\n" + kStep); }),
                  "*END STEP before any *STEP");
}

TEST_F(DeckTest, QuadraticFaceWeightsAreTheConsistentNodalShares) {
  const InputDeck deck = read(two_hexes() + kStep);
  // Face S1 (z = 0) of element 1: 1 x 1. Corners get -A/12, mid-sides A/3 (serendipity).
  const auto face = calculix::face_geometry(deck, {1, 1});
  ASSERT_EQ(face.nodes.size(), 8u);
  EXPECT_NEAR(face.area, 1.0, 1e-14);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(face.weights[i], -1.0 / 12, 1e-14);
  for (int i = 4; i < 8; ++i) EXPECT_NEAR(face.weights[i], 1.0 / 3, 1e-14);
  EXPECT_TRUE(face.centroid.isApprox(Eigen::Vector3d(0.5, 0.5, 0.0), 1e-14));
  // A pressure's nodal forces: the same shares along the outward normal (-z for the face at
  // the bottom of the element).
  for (int i = 0; i < 8; ++i)
    EXPECT_TRUE(
        face.normal_weights.row(i).isApprox(face.weights[i] * Eigen::RowVector3d(0, 0, -1), 1e-14))
        << "node " << i << ": " << face.normal_weights.row(i);
  // The opposite face, S2 (z = 1), points up.
  const auto top = calculix::face_geometry(deck, {1, 2});
  EXPECT_TRUE(top.normal_weights.colwise().sum().isApprox(Eigen::RowVector3d(0, 0, 1), 1e-14));
  EXPECT_THROW(calculix::face_geometry(deck, {1, 7}), DeckError);
}

TEST_F(DeckTest, SectorFaceAreaIsTheArcTimesTheLength) {
  SectorCylinder cylinder;
  const InputDeck deck = read(cylinder.deck());
  const auto face = calculix::face_geometry(deck, deck.surface("INNER").front());
  EXPECT_NEAR(face.area, cylinder.inner_area(), 1e-9 * cylinder.inner_area());
  EXPECT_NEAR(face.centroid.head<2>().norm(), cylinder.ri, 1e-4 * cylinder.ri);
  // The curved bore's normal turns across the face: summed, it is the area times the mean
  // cosine, sin(a / 2) / (a / 2) for the sector's angle a, along the centroid's inward radius.
  const Eigen::Vector3d inward =
      -Eigen::Vector3d(face.centroid.x(), face.centroid.y(), 0).normalized();
  const Eigen::Vector3d sum = face.normal_weights.colwise().sum().transpose();
  const double half = cylinder.angle_degrees / 2 * kPi / 180;
  EXPECT_NEAR(sum.dot(inward), face.area * std::sin(half) / half, 1e-9 * face.area);
  EXPECT_NEAR((sum - sum.dot(inward) * inward).norm(), 0.0, 1e-9 * face.area);
}

TEST_F(DeckTest, PlaneElementEdgesCountTheThickness) {
  testing::PlaneStrainStrip strip;
  const InputDeck deck = read(strip.deck());
  const auto face = calculix::face_geometry(deck, deck.surface("TOP").front());
  const double area = strip.lx / strip.nx * strip.thickness;
  EXPECT_NEAR(face.area, area, 1e-14);
  EXPECT_NEAR(face.weights[0], area / 6, 1e-14);
  EXPECT_NEAR(face.weights[1], area / 6, 1e-14);
  EXPECT_NEAR(face.weights[2], 2 * area / 3, 1e-14);
}

// Edges of axisymmetric elements stand for the rings they sweep (ccx takes the *CLOAD of CAX
// models per 360 degrees): area 2 pi r L on the bore, pi (r2^2 - r1^2) on an end, the weights
// integrals of N_i 2 pi r, the centroid weighted by the radius.
TEST_F(DeckTest, AxisymmetricEdgesAreRings) {
  SectorCylinder cylinder;
  cylinder.element_type = "CAX8";
  const InputDeck deck = read(cylinder.deck());
  const auto bore = calculix::face_geometry(deck, deck.surface("INNER").front());
  const double ring = cylinder.inner_area();  // 2 pi ri L
  EXPECT_NEAR(bore.area, ring, 1e-12 * ring);
  ASSERT_EQ(bore.weights.size(), 3);
  EXPECT_NEAR(bore.weights[0], ring / 6, 1e-12 * ring);
  EXPECT_NEAR(bore.weights[1], ring / 6, 1e-12 * ring);
  EXPECT_NEAR(bore.weights[2], 2 * ring / 3, 1e-12 * ring);
  EXPECT_TRUE(bore.centroid.isApprox(Eigen::Vector3d(cylinder.ri, cylinder.length / 2, 0), 1e-12));
  // The bore's outward normal (out of the wall) points to the axis: -x.
  for (int i = 0; i < 3; ++i)
    EXPECT_TRUE(
        bore.normal_weights.row(i).isApprox(bore.weights[i] * Eigen::RowVector3d(-1, 0, 0), 1e-12));

  const auto end = calculix::face_geometry(deck, deck.surface("TOP").front());  // element 1
  const double r1 = cylinder.ri, r2 = cylinder.radius(2);
  const double annulus = kPi * (r2 * r2 - r1 * r1);
  EXPECT_NEAR(end.area, annulus, 1e-12 * annulus);
  EXPECT_NEAR(end.weights.sum(), annulus, 1e-12 * annulus);
  // Node 3 (outer end) carries more of the ring than node 4 (inner end).
  EXPECT_GT(end.weights[0], end.weights[1]);
  const double centroid_radius = 2.0 / 3.0 * (r2 * r2 * r2 - r1 * r1 * r1) / (r2 * r2 - r1 * r1);
  EXPECT_NEAR(end.centroid.x(), centroid_radius, 1e-12 * r2);
  EXPECT_NEAR(end.centroid.y(), cylinder.length, 1e-12 * cylinder.length);

  const InputDeck linear = read(
      "*NODE\n1, 1, 0\n2, 2, 0\n3, 2, 1\n4, 1, 1\n*ELEMENT, TYPE=CAX4, ELSET=E\n1, 1, 2, 3, 4\n" +
      kStep);
  const auto edge = calculix::face_geometry(linear, {1, 4});  // r = 1, length 1
  EXPECT_NEAR(edge.area, 2 * kPi, 1e-12);
  EXPECT_NEAR(edge.weights[0], kPi, 1e-12);
}

// In an NLGEOM step the traction acts on the faces as they have moved: a bore pushed out by
// d is the ring 2 pi (ri + d) L, and its nodal forces follow.
TEST_F(DeckTest, MovedFacesCarryTheirTractionOnTheCurrentRing) {
  SectorCylinder cylinder;
  cylinder.element_type = "CAX8";
  const InputDeck deck = read(cylinder.deck());
  calculix::InterfaceLoads loads(deck, deck.surface("INNER"));
  const double d = 0.05 * cylinder.ri;
  calculix::NodeDisplacements displacement;
  for (const auto& geometry : loads.geometry())
    for (const auto node : geometry.nodes) displacement[node] = Eigen::Vector3d(d, 0.0, 0.0);
  loads.move_faces(displacement);
  double area = 0.0;
  for (const auto& geometry : loads.geometry()) area += geometry.area;
  const double ring = 2 * kPi * (cylinder.ri + d) * cylinder.length;
  EXPECT_NEAR(area, ring, 1e-12 * ring);
  RowMatrix traction = RowMatrix::Zero(static_cast<Eigen::Index>(loads.faces().size()), 3);
  traction.col(1).setConstant(2.0);  // axial
  double axial = 0.0;
  for (const auto& [node, force] : loads.nodal_forces(traction)) axial += force.y();
  EXPECT_NEAR(axial, 2.0 * ring, 1e-12 * ring);
}

TEST_F(DeckTest, LoadsFileHasPressuresAndRotatedNodalForces) {
  SectorCylinder cylinder;
  const InputDeck deck = read(cylinder.deck());
  calculix::InterfaceLoads loads(deck, deck.surface("INNER"));
  Eigen::VectorXd pressure = Eigen::VectorXd::Constant(1, 1.2345678901234567e5);
  RowMatrix traction(1, 3);
  traction << 0.0, 0.0, 2.0;  // axial: the same in the nodes' cylindrical systems
  loads.write(directory_ / "loads.inp", pressure, traction);
  const std::string text = read_text(directory_ / "loads.inp");
  EXPECT_CONTAINS(text, "*DLOAD\n1, P6, 1.2345678901235E+05\n*CLOAD\n");
  double axial = 0.0;
  for (const auto& [node, force] : loads.nodal_forces(traction)) axial += force.z();
  // The quadratic face approximates the arc: 1e-10 relative at 1 degree.
  EXPECT_NEAR(axial, 2.0 * cylinder.inner_area(), 1e-9 * cylinder.inner_area());
  // A radial traction at the face centre has no axial part in any node's system.
  const Eigen::Vector3d e_r = loads.geometry().front().centroid.normalized();
  traction.row(0) = e_r.transpose();
  loads.write(directory_ / "loads.inp", pressure, traction);
  std::istringstream lines(read_text(directory_ / "loads.inp"));
  std::string line;
  while (std::getline(lines, line) && line != "*CLOAD") {
  }
  double hoop = 0.0, radial = 0.0;
  while (std::getline(lines, line)) {
    long node;
    int dof;
    double value;
    ASSERT_EQ(std::sscanf(line.c_str(), "%ld, %d, %lf", &node, &dof, &value), 3) << line;
    (dof == 1 ? radial : dof == 2 ? hoop : radial) += dof == 3 ? 0.0 : std::abs(value);
  }
  EXPECT_LT(hoop, 1e-2 * radial);  // at most 0.25 degree off radial
}

TEST(CcxNumber, FitsTwentyCharacters) {
  for (const double value : {-1.2345678901234567e-98, 1e300, -0.1, 3.0, 123456789.0})
    EXPECT_LE(calculix::ccx_number(value).size(), 20u) << value;
  EXPECT_EQ(calculix::ccx_number(1e-120), "0.");
  EXPECT_DOUBLE_EQ(std::stod(calculix::ccx_number(-0.1)), -0.1);
}

TEST(DatFile, ReadsTheLastBlockOfTheSet) {
  TemporaryDirectory directory;
  write_text(directory / "job.dat",
             "\n displacements (vx,vy,vz) for set IFACE and time  0.5000000E+00\n\n"
             "         2  1.000000E+00  2.000000E+00  3.000000E+00\n"
             "         1  4.000000E+00  5.000000E+00  6.000000E+00\n\n"
             " displacements (vx,vy,vz) for set OTHER and time  0.1000000E+01\n\n"
             "         1  9.000000E+00  9.000000E+00  9.000000E+00\n\n"
             " displacements (vx,vy,vz) for set IFACE and time  0.1000000E+01\n\n"
             "         2  1.500000E+00  2.500000E+00  3.500000E+00\n"
             "         1 -4.500000E-03  5.500000E+00  6.500000E+00\n\n");
  const RowMatrix values =
      calculix::read_node_print(directory / "job.dat", "displacements", "iface", {1, 2});
  EXPECT_DOUBLE_EQ(values(0, 0), -4.5e-3);
  EXPECT_DOUBLE_EQ(values(1, 2), 3.5);
  EXPECT_THROW(calculix::read_node_print(directory / "job.dat", "displacements", "IFACE", {3}),
               std::runtime_error);
  EXPECT_THROW(calculix::read_node_print(directory / "job.dat", "displacements", "NONE", {1}),
               std::runtime_error);
}

// A restarted step 80 whose full increment diverged ("1U") and converged at a quarter.
TEST(StaFile, ReadsTheAttemptsAndTheFirstConvergedIncrement) {
  TemporaryDirectory directory;
  write_text(directory / "job.sta",
             "SUMMARY OF JOB INFORMATION\n"
             "  STEP      INC     ATT  ITRS     TOT TIME     STEP TIME      INC TIME\n"
             "    80          1     1U    4  0.790000E-02  0.000000E+00  0.100000E-03\n"
             "    80          1     2     4  0.792500E-02  0.250000E-04  0.250000E-04\n"
             "    80          2     1     3  0.795000E-02  0.500000E-04  0.250000E-04\n"
             "    80          3     1     2  0.798750E-02  0.875000E-04  0.375000E-04\n");
  const auto attempts = calculix::read_sta(directory / "job.sta");
  ASSERT_EQ(attempts.size(), 4U);
  EXPECT_FALSE(attempts[0].converged);
  EXPECT_EQ(attempts[0].newton_iterations, 4);
  EXPECT_TRUE(attempts[1].converged);
  EXPECT_EQ(attempts[3].increment, 3);
  EXPECT_DOUBLE_EQ(*calculix::first_converged_increment(attempts), 0.25e-4);
  EXPECT_DOUBLE_EQ(*calculix::carried_initial_increment(attempts, 1e-4), 0.25e-4);
  // Deeper cut-backs are carried as one: a quarter of the deck's increment.
  EXPECT_DOUBLE_EQ(*calculix::carried_initial_increment(attempts, 4e-4), 1e-4);
  // A replayed run lists the committed steps first: the last step's increment counts.
  write_text(directory / "replay.sta",
             "    1          1     1     2  0.100000E+01  0.100000E+01  0.100000E+01\n"
             "    2          1     1U    5  0.100000E+01  0.000000E+00  0.100000E+01\n");
  EXPECT_FALSE(calculix::first_converged_increment(calculix::read_sta(directory / "replay.sta")));
  EXPECT_FALSE(
      calculix::carried_initial_increment(calculix::read_sta(directory / "replay.sta"), 1.0));
  EXPECT_TRUE(calculix::read_sta(directory / "none.sta").empty());
}

TEST(CcxErrors, QuotesEachErrorMessage) {
  const std::string log =
      " *WARNING reading *STATIC:\n   changed\n\n *ERROR reading *DLOAD: element set\n"
      "        or facial surface TOPX\n        has not yet been defined. \n\n"
      " STEP 1\n *ERROR in calinput: at least one fatal\n        error message\n";
  const std::string messages = calculix::error_messages(log);
  EXPECT_CONTAINS(messages, "*ERROR reading *DLOAD");
  EXPECT_CONTAINS(messages, "TOPX");
  EXPECT_EQ(messages.find("WARNING"), std::string::npos);
  EXPECT_EQ(messages.find("calinput"), std::string::npos);
}

// The wrapper's errors that need no real ccx.
class CalculixWithoutCcx : public ::testing::Test {
 protected:
  /// A stand-in for ccx: a shell script with `body`.
  std::string fake_ccx(const std::string& body) {
    const auto script = test_.path("wall/fake_ccx");
    write_text(script, "#!/bin/sh\n" + body + "\n");
    ::chmod(script.c_str(), 0755);
    return "executable: ./fake_ccx\n";
  }
  /// The message of the input a fake ccx running `body` rejects in time step `step`.
  std::string rejection_by(const std::string& body, int step) {
    test_.create(cylinder_.deck(), fake_ccx(body));
    test_.wrapper().initialize();
    test_.wrapper().initialize_step(step, step);
    return testing::error_message<SolverRejectedInput>([&] { test_.solve(1e6); });
  }
  CalculixCase test_;
  SectorCylinder cylinder_;
};

TEST_F(CalculixWithoutCcx, MissingCcxSaysHowToInstallIt) {
  test_.create(cylinder_.deck(), "executable: no-such-ccx\n");
  const std::string message = testing::error_message<CaseError>([&] { test_.wrapper().check(); });
  EXPECT_CONTAINS(message, "case.yaml");
  EXPECT_CONTAINS(message, "no-such-ccx");
  EXPECT_CONTAINS(message, "install the Debian package calculix-ccx");
}

TEST_F(CalculixWithoutCcx, CrashIsReportedWithSignalAndPosition) {
  test_.create(cylinder_.deck(), fake_ccx("echo reading the deck\nkill -SEGV $$"));
  test_.wrapper().initialize();
  test_.wrapper().initialize_step(1, 1.0);
  const std::string message = testing::error_message<SolverError>([&] { test_.solve(1e6); });
  EXPECT_CONTAINS(message, "ccx killed by signal 11");
  EXPECT_CONTAINS(message, "time step 1, coupling iteration 1");
  EXPECT_CONTAINS(message, "reading the deck");
}

// ccx gives up an increment either below the minimum size or after too many cutbacks: both
// are non-convergence (with what to change), not a deck error.
TEST_F(CalculixWithoutCcx, TooManyCutbacksIsNonConvergence) {
  const std::string message = rejection_by(
      "echo ' too slow convergence; the increment size is decreased'\n"
      "echo ' *ERROR: too many cutbacks'\nexit 201",
      3);
  EXPECT_CONTAINS(message, "ccx did not converge at time step 3, coupling iteration 1");
  EXPECT_CONTAINS(message, "cut back too often");
  EXPECT_CONTAINS(message, "what to change");
  EXPECT_EQ(message.find("rejected the input deck"), std::string::npos) << message;
}

TEST_F(CalculixWithoutCcx, TooManyIncrementsIsNonConvergence) {
  const std::string message =
      rejection_by("echo ' *ERROR in nonlingeo: max. # of increments reached'\nexit 201", 2);
  EXPECT_CONTAINS(message, "ccx did not converge at time step 2, coupling iteration 1");
  EXPECT_CONTAINS(message, "more increments than *STEP, INC= allows");
}

TEST_F(CalculixWithoutCcx, HangIsStoppedAfterTheTimeout) {
  test_.create(cylinder_.deck(), fake_ccx("exec sleep 30") + "timeout: 0.3\n");
  test_.wrapper().initialize();
  test_.wrapper().initialize_step(1, 1.0);
  const auto start = std::chrono::steady_clock::now();
  const std::string message = testing::error_message<SolverError>([&] { test_.solve(1e6); });
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 5.0);
  EXPECT_CONTAINS(message, "ccx did not finish within 0.3 s at time step 1, coupling iteration 1");
}

TEST_F(CalculixWithoutCcx, MissingResultsAreReported) {
  test_.create(cylinder_.deck(), fake_ccx("exit 0"));
  test_.wrapper().initialize();
  test_.wrapper().initialize_step(1, 1.0);
  EXPECT_CONTAINS(testing::error_message<SolverError>([&] { test_.solve(1e6); }),
                  "cannot read ccx's results file");
}

// ccx's threads are its own (`threads:`); CHOLMOD and OpenBLAS inside it get one each, or they
// oversubscribe the machine (docs/solver-wrappers-calculix.md: a third of the wire drawing
// case's time went to waking and yielding their threads).
TEST_F(CalculixWithoutCcx, CcxGetsItsThreadsAndItsLibrariesOne) {
  // Only the variables the wrapper sets: a machine may set others of OpenBLAS's (its core type).
  test_.create(cylinder_.deck(),
               fake_ccx("env | grep -E '^(OMP_NUM_THREADS|OMP_THREAD_LIMIT|OPENBLAS_NUM_THREADS|"
                        "CCX_NPROC_[A-Z_]+|GLIBC_TUNABLES)=' | sort > thread_env.txt") +
                   "threads: 2\n");
  test_.wrapper().initialize();
  test_.wrapper().initialize_step(1, 1.0);
  EXPECT_THROW(test_.solve(1e6), SolverError);  // the fake ccx writes no results
  // The huge-page tunable is added to the coupler's own tunables, if it has any.
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const std::string huge_pages = std::string(tunables && *tunables ? tunables : "") +
                                 (tunables && *tunables ? ":" : "") + "glibc.malloc.hugetlb=1";
  EXPECT_EQ(read_text(test_.path("wall/thread_env.txt")),
            "CCX_NPROC_EQUATION_SOLVER=2\nCCX_NPROC_RESULTS=2\nCCX_NPROC_STIFFNESS=2\n"
            "GLIBC_TUNABLES=" +
                huge_pages + "\nOMP_NUM_THREADS=2\nOMP_THREAD_LIMIT=1\nOPENBLAS_NUM_THREADS=1\n");
}

TEST_F(CalculixWithoutCcx, CaseKeysAreChecked) {
  EXPECT_CONTAINS(testing::error_message<CaseError>(
                      [&] { test_.create(cylinder_.deck(), "input_variables: [forse]\n"); }),
                  "the loads are pressure and traction, or force");
  EXPECT_CONTAINS(testing::error_message<CaseError>([&] {
                    test_.create(cylinder_.deck(), "input_variables: [pressure, force]\n");
                  }),
                  "force is each face's whole load");
  test_.create(cylinder_.deck(), fake_ccx("exit 0"), "NOSUCH");
  EXPECT_CONTAINS(testing::error_message<CaseError>([&] { test_.wrapper().initialize(); }),
                  "no element-face surface NOSUCH");
}

TEST_F(CalculixWithoutCcx, CarriedIncrementNeedsTheProcedureDataLine) {
  std::string deck = cylinder_.deck();
  deck.erase(deck.find("0.25, 1.0\n"), 10);  // *STATIC without data: ccx's defaults
  test_.create(deck, "executable: /bin/true\ninitial_increment: previous_iteration\n");
  const std::string message =
      testing::error_message<CaseError>([&] { test_.wrapper().initialize(); });
  EXPECT_CONTAINS(message, "case.yaml:");
  EXPECT_CONTAINS(message, "the *STATIC card of wall.inp has no data line");
  EXPECT_CONTAINS(testing::error_message<CaseError>(
                      [&] { test_.create(cylinder_.deck(), "initial_increment: last\n"); }),
                  "initial_increment");
}

TEST_F(CalculixWithoutCcx, DynamicStepMustSpanTheCouplingTimeStep) {
  std::string deck = cylinder_.deck();
  deck.replace(deck.find("*STATIC\n0.25, 1.0"), 17, "*DYNAMIC\n0.25, 1.0");
  CalculixCase test(0.5);
  test.create(deck, "executable: /bin/true\n");
  EXPECT_CONTAINS(testing::error_message<CaseError>([&] { test.wrapper().initialize(); }),
                  "the *DYNAMIC step's time period is 1, the coupling time step delta_t is 0.5");
}

// ccx restarts its integrator at every step with full integration: reduced-integration elements
// in a dynamic deck would grow without bound over the coupling time steps (one step each).
TEST_F(CalculixWithoutCcx, DynamicDeckRefusesReducedIntegrationElements) {
  SectorCylinder cylinder;
  cylinder.procedure = "*DYNAMIC, DIRECT, ALPHA=0";
  cylinder.increments = "0.5, 0.5";
  cylinder.density = 7850.0;
  CalculixCase test(0.5);
  test.create(cylinder.deck(), "executable: /bin/true\n");
  const std::string message =
      testing::error_message<CaseError>([&] { test.wrapper().initialize(); });
  EXPECT_CONTAINS(message, "wall.inp:");
  EXPECT_CONTAINS(message, "element 1 is a C3D20R (reduced integration) in a *DYNAMIC deck");
  EXPECT_CONTAINS(message, "Use the fully integrated element (C3D20)");
  EXPECT_CONTAINS(message, "allow_reduced_integration: true");

  cylinder.element_type = "CAX8R";  // expanded into C3D20R
  test.create(cylinder.deck(), "executable: /bin/true\n");
  EXPECT_CONTAINS(testing::error_message<CaseError>([&] { test.wrapper().initialize(); }),
                  "element 1 is a CAX8R (reduced integration) in a *DYNAMIC deck");
  cylinder.element_type = "C3D20R";

  test.create(cylinder.deck(), "executable: /bin/true\nallow_reduced_integration: true\n");
  EXPECT_NO_THROW(test.wrapper().initialize());
  cylinder.element_type = "C3D20";
  test.create(cylinder.deck(), "executable: /bin/true\n");
  EXPECT_NO_THROW(test.wrapper().initialize());
  // Static steps integrate consistently: reduced integration is fine there.
  test.create(SectorCylinder{}.deck(), "executable: /bin/true\n");
  EXPECT_NO_THROW(test.wrapper().initialize());
}

}  // namespace
}  // namespace cocopp
