// The wire drawing case (examples/wire_drawing) coupled end to end, coarse and short: the film
// (3 x 50 cells) and the wire (4 x 153 CAX8) through the sliding interface for 11 time steps,
// the die held for 10 and closing in the 11th. Checks that the run completes with the paper's
// coupling (IQN-ILS, 0.01 um) in a few iterations per step, and that film thickness and
// pressure are where lubrication and the die schedule put them, and that plot.py draws the run.
// The whole 80-step case is not a test (docs/wire-drawing.md). Needs OpenFOAM and ccx.
#include <gtest/gtest.h>

#include <cmath>

#include "coupler/results/results_reader.hpp"
#include "tests/integration/run_helpers.hpp"
#include "tests/support/wire_drawing_case.hpp"

namespace cocopp {
namespace {

namespace fs = std::filesystem;

// examples/wire_drawing/parameters.yaml
constexpr double kGap = 10e-6, kEntry = 1.0e-3, kClosingPerStep = 38.53e-6 / 70;

TEST(WireDrawingCase, CoarseShortRunCouplesFilmAndWire) {
  testing::TemporaryDirectory directory;
  testing::write_wire_drawing_case(
      directory.path(),
      "--set mesh.wire_radial_elements=4"
      " --set mesh.wire_axial_elements=153"
      " --set mesh.film_axial_cells=50 --set mesh.film_radial_cells=3");
  testing::edit(directory / "case.yaml", "number_of_timesteps: 80", "number_of_timesteps: 11");
  const testing::CommandResult run =
      testing::run_cocopp("run -q " + (directory / "case.yaml").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;

  const ResultsReader results(directory / "results/case.h5");
  EXPECT_EQ(results.status(), "completed");
  ASSERT_EQ(results.steps().size(), 11u);
  const auto iterations = results.dataset("steps/iterations").values;
  double total = 0.0, most = 0.0;
  for (double n : iterations) total += n, most = std::max(most, n);
  std::printf("iterations per step: %.2f on average, at most %.0f\n", total / 11, most);
  EXPECT_LE(total / 11, 5.33);  // the paper's average
  EXPECT_LE(most, 8.0);

  // The film's wall points (x, y in the wedge plane, z along the axis) at the last step.
  const auto points = results.dataset("x/wire_points/coordinates");
  const auto displacement = results.dataset("x/wire_points/displacement");
  const auto pressure = results.dataset("y/wire_faces/pressure");
  const std::size_t n = points.shape[0], last = 10;
  double thinnest = 1.0, thickest = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (points.values[3 * i + 2] < kEntry + 50e-6) continue;  // the bearing
    const double x = points.values[3 * i], y = points.values[3 * i + 1];
    const double ux = displacement.values[3 * (last * n + i)];
    const double uy = displacement.values[3 * (last * n + i) + 1];
    const double radial = (x * ux + y * uy) / std::hypot(x, y);  // outwards
    const double film = kGap - kClosingPerStep - radial;
    thinnest = std::min(thinnest, film);
    thickest = std::max(thickest, film);
  }
  double peak = 0.0;
  for (std::size_t i = last * pressure.row_size(); i < (last + 1) * pressure.row_size(); ++i)
    peak = std::max(peak, pressure.values[i]);
  std::printf("step 11: film in the bearing %.3f .. %.3f um, peak pressure %.3g Pa\n",
              1e6 * thinnest, 1e6 * thickest, peak);
  // The wire yields to the film only elastically so far (the die has closed by 0.55 um).
  EXPECT_GT(thinnest, 8.5e-6);
  EXPECT_LT(thickest, 10.5e-6);
  EXPECT_GT(peak, 4e8);
  EXPECT_LT(peak, 1.25e9);

  // The figures of docs/wire-drawing.md come from plot.py: it draws this run too.
  testing::run_in(
      directory.path(),
      "/usr/bin/python3 " + (testing::kWireDrawingExample / "plot.py").string() + " . -o plot.png");
  EXPECT_GT(fs::file_size(directory / "plot.png"), 10000u);
}

}  // namespace
}  // namespace cocopp
