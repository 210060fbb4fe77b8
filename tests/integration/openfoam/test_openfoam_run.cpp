// `cocopp run` on the OpenFOAM wedge tube example (examples/tube/openfoam_wedge), shortened to
// 10 time steps: the whole coupled path (coupler, quasi-Newton iterations, mappers with the
// axisymmetric transformers, cocoppPimpleFoam, the tube structure). Needs OpenFOAM.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/integration/run_helpers.hpp"

namespace cocopp {
namespace {

namespace fs = std::filesystem;
using testing::copy_example;
using testing::read_dataset;
using testing::read_json;
using testing::read_text;
using testing::run_cocopp;
using testing::run_command;
using testing::write_text;

constexpr int kSteps = 10;

TEST(OpenFoamWedgeExample, CouplesTheWedgeToTheTubeStructure) {
  const fs::path dir = copy_example("tube/openfoam_wedge", "openfoam_wedge");
  for (const auto& entry : fs::directory_iterator(dir / "fluid"))  // output of earlier runs
    if (entry.is_directory() && entry.path().filename() != "0" &&
        entry.path().filename() != "constant" && entry.path().filename() != "system")
      fs::remove_all(entry.path());
  std::string case_text = read_text(dir / "case.yaml");
  const std::string steps = "number_of_timesteps: 100";
  ASSERT_NE(case_text.find(steps), std::string::npos);
  case_text.replace(case_text.find(steps), steps.size(),
                    "number_of_timesteps: " + std::to_string(kSteps));
  write_text(dir / "case.yaml", case_text);
  const auto mesh = run_command("cd " + (dir / "fluid").string() +
                                " && WM_PROJECT_DIR=/usr/share/openfoam blockMesh");
  ASSERT_EQ(mesh.exit_code, 0) << mesh.output;

  const auto run = run_cocopp("run " + (dir / "case.yaml").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const auto summary = read_json(dir / "results" / "case.summary.json");
  EXPECT_TRUE(summary["completed"].get<bool>());
  EXPECT_EQ(summary["steps_completed"].get<int>(), kSteps);

  const fs::path results = dir / "results" / "case.h5";
  const auto iterations = read_dataset(results, "steps/iterations");
  ASSERT_EQ(iterations.size(), static_cast<std::size_t>(kSteps));
  for (int step = 2; step <= kSteps; ++step)  // the first step may end at the limit (15)
    EXPECT_LT(iterations[step - 1], 15) << "step " << step;

  // The pulse enters at z = -0.025 and travels at about sqrt(E h / (rho d)) = 5.5 m/s: after
  // 1 ms it has not reached the second half of the tube.
  const auto z = read_dataset(results, "y/wall_faces/coordinates");
  const auto pressure = read_dataset(results, "y/wall_faces/pressure");
  const std::size_t faces = z.size() / 3;
  ASSERT_EQ(faces, 100u);
  const std::size_t last = pressure.size() - faces;  // the last step's row
  double inlet_pressure = 0.0, downstream_pressure = 0.0;
  for (std::size_t i = 0; i < faces; ++i) {
    if (z[3 * i + 2] < -0.024) inlet_pressure = pressure[last + i];
    if (z[3 * i + 2] > 0.0)
      downstream_pressure = std::max(downstream_pressure, std::abs(pressure[last + i]));
  }
  EXPECT_GT(inlet_pressure, 0.8 * 1333.2);
  EXPECT_LT(inlet_pressure, 1.2 * 1333.2);
  EXPECT_LT(downstream_pressure, 0.01 * inlet_pressure);

  // The wall moves radially on both wedge faces (x = +-r sin 2.5 deg): the displacement
  // keeps the wedge a wedge, x / y = x0 / y0.
  const auto points = read_dataset(results, "x/wall_points/coordinates");
  const auto displacement = read_dataset(results, "x/wall_points/displacement");
  const std::size_t n = points.size() / 3, row = displacement.size() - 3 * n;
  double largest = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double dx = displacement[row + 3 * i], dy = displacement[row + 3 * i + 1];
    EXPECT_NEAR(dx * points[3 * i + 1], dy * points[3 * i], 1e-12 * std::abs(dy) + 1e-20);
    EXPECT_DOUBLE_EQ(displacement[row + 3 * i + 2], 0.0);
    largest = std::max(largest, dy);
  }
  EXPECT_GT(largest, 1e-6);  // the pulse widens the tube near the inlet (m)
  fs::remove_all(dir);
}

}  // namespace
}  // namespace cocopp
