// Substeps (waveform iteration): the built-in tube solvers taking several steps of their own
// per coupling time step, through the protocol's SUBSTEPS and the SDK's windows.
// - Windows of 4 substeps on both solvers are the same discrete problem as coupling every
//   substep: the same solution to the coupling tolerance, in a quarter of the iterations.
// - A restart continues the windows bit for bit.
// - What cannot take substeps says so.
// Their accuracy against resolved references: test_coupling_accuracy.cpp (Release only).
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "tests/integration/run_helpers.hpp"
#include "tests/integration/variant_runs.hpp"

using namespace cocopp::testing;
namespace fs = std::filesystem;

namespace {

TEST(Substeps, WindowsOfSubstepsAreCouplingEverySubstepInFewerIterations) {
  const fs::path windows =
      run_variant("tube/flow_structure", "substeps_windows", {1e-4, 100, 4, 4});
  const fs::path every = run_variant("tube/flow_structure", "substeps_every", {2.5e-5, 400});
  // Measured 8.1e-11 (largest difference over the largest displacement): the coupling's
  // tolerance, 1e-9 relative, apart.
  EXPECT_LT(relative_difference(radial(every, 4), radial(windows)), 1e-8);
  const int window_iterations =
      total_iterations(read_json(windows / "results" / "case.summary.json"));
  const int every_iterations = total_iterations(read_json(every / "results" / "case.summary.json"));
  EXPECT_LT(window_iterations, every_iterations / 3)
      << window_iterations << " " << every_iterations;
  fs::remove_all(windows);
  fs::remove_all(every);
}

// The SDK saves a window's restart data under its last substep and reads it back: 50 steps,
// then --restart to 100, gives the uninterrupted run bit for bit.
TEST(Substeps, ARestartContinuesTheWindowsBitForBit) {
  auto prepare = [](const std::string& tag) {
    const fs::path dir = copy_example("tube/flow_structure", tag);
    edit(dir / "case.yaml", "    name: flow\n", "    name: flow\n    substeps: 4\n");
    return dir;
  };
  const fs::path whole = prepare("substeps_whole"), parts = prepare("substeps_parts");
  ASSERT_EQ(run_cocopp("run -q " + (whole / "case.yaml").string()).exit_code, 0);
  edit(parts / "case.yaml", "number_of_timesteps: 100", "number_of_timesteps: 50");
  ASSERT_EQ(run_cocopp("run -q " + (parts / "case.yaml").string()).exit_code, 0);
  edit(parts / "case.yaml", "number_of_timesteps: 50", "number_of_timesteps: 100");
  const CommandResult restarted = run_cocopp("run -q --restart " + (parts / "case.yaml").string());
  ASSERT_EQ(restarted.exit_code, 0) << restarted.output;
  for (const char* dataset : {"x/wall/displacement", "y/wall/pressure", "steps/iterations"})
    EXPECT_EQ(read_dataset(whole / "results" / "case.h5", dataset),
              read_dataset(parts / "results" / "case.h5", dataset))
        << dataset;
  fs::remove_all(whole);
  fs::remove_all(parts);
}

std::string failing_run(const std::string& tag,
                        const std::vector<std::pair<std::string, std::string>>& edits) {
  const fs::path dir = copy_example("tube/flow_structure", tag);
  edit(dir / "case.yaml", "    name: flow\n", "    name: flow\n    substeps: 2\n");
  for (const auto& [from, to] : edits) edit(dir / "case.yaml", from, to);
  const CommandResult run = run_cocopp("run -q " + (dir / "case.yaml").string());
  EXPECT_NE(run.exit_code, 0) << run.output;
  fs::remove_all(dir);
  return run.output;
}

TEST(Substeps, WhatCannotIterateOnWindowsSaysSo) {
  std::string out =
      failing_run("substeps_parallel", {{"  type: iqni\n",
                                         "  type: iqni\n  scheme: parallel\n  load_criterion: "
                                         "{type: absolute_norm, tolerance: 1.0e-4}\n"}});
  EXPECT_NE(out.find("solver 'flow' takes 2 substeps a time step, which the parallel scheme "
                     "does not yet iterate on: use scheme serial"),
            std::string::npos)
      << out;
  out = failing_run("substeps_ibqn",
                    {{"  type: iqni\n", "  type: ibqn\n  model_s: {type: ls, q: 10}\n"},
                     {"  model:\n", "  model_f:\n"}});
  EXPECT_NE(out.find("coupled solver 'ibqn' cannot iterate on windows of substeps"),
            std::string::npos)
      << out;
}

}  // namespace
