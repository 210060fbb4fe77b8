// examples/tube/flow_calculix run as a user runs it (`cocopp run`), shortened to 10 time steps:
// the case file's calculix wrapper behind a mapped wrapper, coupled to the tube flow, against
// the flow-structure tube example (the same tube with its 1D structure model). Needs ccx.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "run_helpers.hpp"

using namespace cocopp::testing;
namespace fs = std::filesystem;

namespace {

/// The largest radial (y) wall displacement at time step `step` (1-based) of a results file.
double peak_radial(const fs::path& results, int step, std::size_t points) {
  const auto values = read_dataset(results, "x/wall/displacement");
  const std::size_t row = static_cast<std::size_t>(step - 1) * points * 3;
  double peak = 0.0;
  for (std::size_t i = 0; i < points; ++i) peak = std::max(peak, values.at(row + 3 * i + 1));
  return peak;
}

}  // namespace

TEST(CalculixExample, TubeWallInCalculixFollowsTheTubeStructure) {
  const fs::path calculix = copy_example("tube/flow_calculix", "flow_calculix");
  const fs::path reference = copy_example("tube/flow_structure", "flow_structure_ref");
  edit(calculix / "case.yaml", "number_of_timesteps: 35", "number_of_timesteps: 10");
  edit(reference / "case.yaml", "number_of_timesteps: 100", "number_of_timesteps: 10");
  const CommandResult run = run_cocopp("run " + (calculix / "case.yaml").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("structure mapped onto calculix"), std::string::npos) << run.output;
  ASSERT_EQ(run_cocopp("run -q " + (reference / "case.yaml").string()).exit_code, 0);
  const auto summary = read_json(calculix / "results" / "case.summary.json");
  EXPECT_TRUE(summary["completed"].get<bool>());
  // Every step converged (below the iteration limit of 15).
  EXPECT_LT(summary["average_iterations"].get<double>(), 15.0);
  // The pulse has run a third of the way in 10 steps. The sector is a thick (h/r0 = 0.2) 3D
  // wall, the tube structure a thin-shell model of the same wall: peaks within 15 % (measured
  // 35.2 and 36.6 micrometres).
  const double sector = peak_radial(calculix / "results" / "case.h5", 10, 100);
  const double shell = peak_radial(reference / "results" / "case.h5", 10, 100);
  EXPECT_GT(shell, 1e-5);
  EXPECT_NEAR(sector, shell, 0.15 * shell);
  fs::remove_all(calculix);
  fs::remove_all(reference);
}
