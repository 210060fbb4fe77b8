// The wire drawing case (examples/wire_drawing) given what it cannot carry, coarse: each run
// stops with a message that names the step, the coupling iteration and what to change, and the
// results up to the last converged step stay readable. (A ccx increment that does not converge
// is tested on the calculix wrapper itself: tests/unit/solver_wrappers/calculix.) Needs OpenFOAM
// and ccx.
#include <gtest/gtest.h>

#include <string>

#include "coupler/results/results_reader.hpp"
#include "tests/integration/run_helpers.hpp"
#include "tests/support/wire_drawing_case.hpp"

namespace cocopp {
namespace {

const std::string kCoarse =
    "--set mesh.wire_radial_elements=4 --set mesh.film_axial_cells=50"
    " --set mesh.film_radial_cells=3";

/// Runs the case made with `arguments` for `steps` steps: its output, and the results file.
testing::CommandResult run_case(const testing::TemporaryDirectory& directory,
                                const std::string& arguments, int steps) {
  testing::write_wire_drawing_case(directory.path(), kCoarse + " " + arguments);
  testing::edit(directory / "case.yaml", "number_of_timesteps: 20",
                "number_of_timesteps: " + std::to_string(steps));
  return testing::run_cocopp("run -q " + (directory / "case.yaml").string());
}

TEST(WireDrawingBadInput, DieClosingFasterThanTheFilmCanCarry) {
  // Held for 2 steps, then closing by 16.7 um per step onto a 10 um film: the die crosses the
  // film's cells in step 3 before the wire can give way.
  testing::TemporaryDirectory directory;
  const auto run = run_case(directory,
                            "--set mesh.wire_axial_elements=153 --set time.held_steps=2"
                            " --set time.steps=20 --set die.reduction=0.64",
                            6);
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("solver_failed after 2 time steps"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("turned"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("inside out"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("What to change: a wall that closes more slowly"), std::string::npos)
      << run.output;
  // The film rejects the input, and each shorter step of the coupled solver alike.
  EXPECT_NE(run.output.find("solver 'film' rejected the input at step 3, iteration 1"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("time step 3, coupling iteration 1: the coupled solver stepped back 4 "
                            "times"),
            std::string::npos)
      << run.output;
  const ResultsReader results(directory / "results/case.h5");
  EXPECT_EQ(results.status(), "solver_failed");
  EXPECT_EQ(results.steps().size(), 2u);
}

TEST(WireDrawingBadInput, WireThatLeavesTheFilm) {
  // A 5 mm wire from z = 1 mm: it overlaps the film (0 .. 1.5 mm) by 0.5 mm and, drawn at
  // 0.1 mm per step, leaves it after 5 steps.
  testing::TemporaryDirectory directory;
  const auto run = run_case(directory,
                            "--set mesh.wire_axial_elements=50 --set wire.length=5.0e-3"
                            " --set wire.start=1.0e-3 --set time.held_steps=20"
                            " --set time.steps=20",
                            8);
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("mapped solver 'wire': the mappers cannot be built"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("left the other's interface"), std::string::npos) << run.output;
  const ResultsReader results(directory / "results/case.h5");
  EXPECT_GE(results.steps().size(), 4u);
  EXPECT_LE(results.steps().size(), 6u);
}

}  // namespace
}  // namespace cocopp
