// The boundary conditions cocoppPimpleFoam adds for a sliding FSI interface, on a thin annular
// film (a 5-degree wedge, tests/integration/openfoam/film): `cocoppSlidingWallVelocity` on the
// coupled wire wall (tangential part exactly the wall's velocity, normal part exactly the mesh's
// swept volume per time and area) and `cocoppRadialDisplacement` on the die (every point moves
// radially by the schedule, exactly). Needs OpenFOAM; built only when CMake found it.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "solver_wrappers/solver_error.hpp"
#include "solver_wrappers/solver_wrapper.hpp"
#include "tests/integration/openfoam/openfoam_files.hpp"
#include "tests/support/solver_wrapper_case.hpp"

namespace cocopp {
namespace {

using testing::read_list_file;
using testing::read_patch_values;
using testing::TemporaryDirectory;

constexpr double kDeltaT = 1e-4;    // system/controlDict
constexpr double kWire = 0.75e-3;   // wire radius (system/blockMeshDict)
constexpr double kDie = 0.80e-3;    // die radius
constexpr double kClosing = -1e-2;  // die: radialDisplacement table ((0 0) (0.001 -1e-05)), m/s
const double kHalfAngle = 2.5 * M_PI / 180.0;

double radius(const std::vector<double>& points, std::size_t i) {
  return std::hypot(points[3 * i], points[3 * i + 1]);
}

class FilmBoundaryConditions : public ::testing::Test {
 protected:
  FilmBoundaryConditions() {
    testing::make_case(
        std::filesystem::path(COCOPP_TEST_SOURCE_DIR) / "tests/integration/openfoam/film",
        directory_ / "film");
    start();
  }
  ~FilmBoundaryConditions() override { wrapper_->finalize(); }

  /// The film's solver started (again, after finalize()) at step `timestep_start`.
  void start(int timestep_start = 0) {
    wrapper_ = testing::initialized_wrapper(
        "type: openfoam\nname: film\nworking_directory: film\nboundary_names: [wire]\n"
        "timeout: 60\n",
        directory_.path(), kDeltaT, timestep_start);
  }

  /// One time step with every wire point moved radially outwards by `growth` from its start.
  void step(int number, double growth) {
    Interface input = wrapper_->input_interface();
    const auto& coordinates = input.parts()[0].model_part->coordinates;
    Eigen::MatrixXd values(coordinates.rows(), 3);
    for (Eigen::Index i = 0; i < coordinates.rows(); ++i) {
      const Eigen::Vector3d radial(coordinates(i, 0), coordinates(i, 1), 0.0);
      values.row(i) = growth * radial.normalized().transpose();
    }
    input.values("wire_points", "displacement") = values;
    wrapper_->initialize_step(number, number * kDeltaT);
    wrapper_->solve(input);
    wrapper_->finalize_step();
  }

  std::filesystem::path written(int step, const std::string& file) const {
    return directory_ / "film" / (step == 1 ? "0.0001" : "0.0002") / file;
  }

  TemporaryDirectory directory_;
  std::unique_ptr<SolverWrapper> wrapper_;
};

TEST_F(FilmBoundaryConditions, SlidingWallTakesTheWallVelocityAndTheMeshNormalVelocity) {
  const double growth = 2e-6;
  step(1, growth);
  const auto velocity = read_patch_values(written(1, "U"), "wire");
  ASSERT_EQ(velocity.size(), 3u * 20u);
  // Each wire face spans the wedge symmetrically about the y axis: its normal is -y. Moving
  // its vertices radially from r0 to r1 sweeps the trapezoid prism of cross section
  // sin cos (r1^2 - r0^2) under a face of area 2 r1 sin L, hence this normal velocity.
  const double r0 = kWire, r1 = kWire + growth;
  const double normal = std::cos(kHalfAngle) * (r1 * r1 - r0 * r0) / (2.0 * r1 * kDeltaT);
  for (std::size_t face = 0; face < 20; ++face) {
    EXPECT_NEAR(velocity[3 * face + 0], 0.0, 1e-12) << "face " << face;
    EXPECT_NEAR(velocity[3 * face + 1], normal, 1e-9 * normal) << "face " << face;
    EXPECT_NEAR(velocity[3 * face + 2], 1.0, 1e-12) << "face " << face;  // wallVelocity
  }
  // In the next step the wall stands still: only the sliding velocity remains.
  step(2, growth);
  const auto still = read_patch_values(written(2, "U"), "wire");
  for (std::size_t face = 0; face < 20; ++face) {
    EXPECT_NEAR(still[3 * face + 1], 0.0, 1e-9 * normal) << "face " << face;
    EXPECT_NEAR(still[3 * face + 2], 1.0, 1e-12) << "face " << face;
  }
}

TEST_F(FilmBoundaryConditions, DieMovesRadiallyByItsSchedule) {
  const auto initial = read_list_file(directory_ / "film/constant/polyMesh/points");
  std::vector<std::size_t> die_points;
  for (std::size_t i = 0; i < initial.size() / 3; ++i)
    if (std::abs(radius(initial, i) - kDie) < 1e-12) die_points.push_back(i);
  ASSERT_EQ(die_points.size(), 42u);  // 21 x 2 points on the die
  for (int number = 1; number <= 2; ++number) {
    step(number, 0.0);
    const auto moved = read_list_file(written(number, "polyMesh/points"));
    const double expected = kDie + kClosing * number * kDeltaT;
    for (const std::size_t i : die_points) {
      EXPECT_NEAR(radius(moved, i), expected, 1e-15) << "point " << i << " step " << number;
      // Along its own radial direction: the angle about the axis and z stay.
      EXPECT_NEAR(std::atan2(moved[3 * i], moved[3 * i + 1]),
                  std::atan2(initial[3 * i], initial[3 * i + 1]), 1e-12);
      EXPECT_NEAR(moved[3 * i + 2], initial[3 * i + 2], 1e-18);
    }
  }
  // The wire, held by the coupler, stays where it was.
  const auto moved = read_list_file(written(2, "polyMesh/points"));
  for (std::size_t i = 0; i < initial.size() / 3; ++i)
    if (std::abs(radius(initial, i) - kWire) < 1e-12) {
      EXPECT_NEAR(radius(moved, i), kWire, 1e-16);
    }
}

// A restart (cocopp run --restart) reads the die's last value back from its time directory,
// a nonuniform list there, and goes on with the schedule.
TEST_F(FilmBoundaryConditions, DieRestartsFromAWrittenTime) {
  step(1, 0.0);
  step(2, 0.0);
  wrapper_->finalize();
  start(2);
  step(3, 0.0);
  const auto initial = read_list_file(directory_ / "film/constant/polyMesh/points");
  const auto moved = read_list_file(directory_ / "film/0.0003/polyMesh/points");
  std::size_t die_points = 0;
  for (std::size_t i = 0; i < initial.size() / 3; ++i)
    if (std::abs(radius(initial, i) - kDie) < 1e-12) {
      EXPECT_NEAR(radius(moved, i), kDie + kClosing * 3 * kDeltaT, 1e-15) << "point " << i;
      ++die_points;
    }
  EXPECT_EQ(die_points, 42u);
}

// An input the film's flow diverges on is rejected with the reason, before a floating-point
// exception can kill the solver, so that the coupler can step back. Here the outer loop is
// made to diverge by over-relaxing the momentum equation (1.15: its continuity error grows
// over a few correctors, as on the wire drawing case's step 40; 1.1 converges, and from 1.2 the
// velocity overflows within a corrector while the continuity error is still small, which the
// check does not see: the film then still dies of SIGFPE, with its log's last lines).
TEST_F(FilmBoundaryConditions, AnInputTheFlowDivergesOnIsRejected) {
  wrapper_->finalize();
  {
    std::ofstream solution(directory_ / "film/system/fvSolution", std::ios::app);
    solution << "PIMPLE { nOuterCorrectors 100; }\n"
                "relaxationFactors { equations { U 1.15; UFinal 1.15; } }\n";
  }
  start();
  try {
    step(1, 0.0);
    FAIL() << "no SolverRejectedInput";
  } catch (const SolverRejectedInput& e) {
    EXPECT_NE(std::string(e.what()).find("the flow diverged in coupling iteration 1"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("What to change"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace cocopp
