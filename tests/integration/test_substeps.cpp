// Substeps (waveform iteration): the built-in tube solvers taking several steps of their own
// per coupling time step, through the protocol's SUBSTEPS and the SDK's windows.
// - Windows of 4 substeps on both solvers are the same discrete problem as coupling every
//   substep: the same solution to the coupling tolerance, in a quarter of the iterations.
// - The flow at a quarter of the coupling step, the structure at the step: closer to a fully
//   resolved run than both at the step (bench/substeps.py has the whole table).
// - The interpolation in time on its own (massless rings: the wall's answer is exact at any
//   time): quadratic's difference to coupling every substep falls as the step does.
// - What cannot take substeps says so.
#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "tests/integration/run_helpers.hpp"

using namespace cocopp::testing;
namespace fs = std::filesystem;

namespace {

int total_iterations(const nlohmann::json& summary) {
  int total = 0;
  for (const auto& iterations : summary["iterations_per_step"]) total += iterations.get<int>();
  return total;
}

/// A number as the case file takes it, to the last digit.
std::string number(double value) {
  std::ostringstream text;
  text << std::setprecision(17) << value;
  return text.str();
}

struct Variant {
  double delta_t;
  int steps;
  int flow_substeps = 1, structure_substeps = 1;
  std::string interpolation = "linear";
  bool time_average = true;
};

/// A copy of `example` run as `variant` says, converged to a relative 1e-9 (1e-11 for the ring
/// model); its directory.
fs::path run_variant(const std::string& example, const std::string& tag, const Variant& variant,
                     double tolerance = 1e-9) {
  const fs::path dir = copy_example(example, tag);
  const fs::path case_file = dir / "case.yaml";
  const std::string tube_steps = example == "tube/flow_structure"
                                     ? "  delta_t: 1.0e-4            # s\n"
                                       "  number_of_timesteps: 100\n"
                                     : "  delta_t: 0.01              # s\n"
                                       "  number_of_timesteps: 100\n";
  edit(case_file, tube_steps,
       "  delta_t: " + number(variant.delta_t) +
           "\n  number_of_timesteps: " + std::to_string(variant.steps) + "\n");
  edit(case_file, "  type: iqni\n",
       "  type: iqni\n  time_interpolation: " + variant.interpolation + "\n  time_average: " +
           (variant.time_average ? "true" : "false") + "\n  divergence: {growth_iterations: 0}\n");
  edit(case_file, "tolerance: 1.0e-6", "tolerance: " + number(tolerance));
  edit(case_file, "maximum: 15", "maximum: 100");
  if (variant.flow_substeps > 1)
    edit(case_file, "    name: flow\n",
         "    name: flow\n    substeps: " + std::to_string(variant.flow_substeps) + "\n");
  if (variant.structure_substeps > 1)
    edit(case_file, "    name: structure\n",
         "    name: structure\n    substeps: " + std::to_string(variant.structure_substeps) + "\n");
  const CommandResult run = run_cocopp("run -q " + case_file.string());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  return dir;
}

/// The radial displacement of a run at every `every`-th step, flattened.
std::vector<double> radial(const fs::path& dir, int every = 1, std::size_t steps = 0) {
  const auto all = read_dataset(dir / "results" / "case.h5", "x/wall/displacement");
  const std::size_t cells = 100, stored = all.size() / (3 * cells);
  std::vector<double> values;
  for (std::size_t step = static_cast<std::size_t>(every) - 1;
       step < stored && (steps == 0 || values.size() < steps * cells);
       step += static_cast<std::size_t>(every))
    for (std::size_t cell = 0; cell < cells; ++cell)
      values.push_back(all[3 * (step * cells + cell) + 1]);
  return values;
}

double relative_l2(const std::vector<double>& a, const std::vector<double>& reference) {
  EXPECT_EQ(a.size(), reference.size());
  double difference = 0.0, norm = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), reference.size()); ++i) {
    difference += (a[i] - reference[i]) * (a[i] - reference[i]);
    norm += reference[i] * reference[i];
  }
  return std::sqrt(difference / norm);
}

TEST(Substeps, WindowsOfSubstepsAreCouplingEverySubstepInFewerIterations) {
  const fs::path windows =
      run_variant("tube/flow_structure", "substeps_windows", {1e-4, 100, 4, 4});
  const fs::path every = run_variant("tube/flow_structure", "substeps_every", {2.5e-5, 400});
  // Measured 8.1e-11 (largest difference over the largest displacement): the coupling's
  // tolerance, 1e-9 relative, apart.
  EXPECT_LT(relative_l2(radial(windows), radial(every, 4)), 1e-8);
  const int window_iterations =
      total_iterations(read_json(windows / "results" / "case.summary.json"));
  const int every_iterations = total_iterations(read_json(every / "results" / "case.summary.json"));
  EXPECT_LT(window_iterations, every_iterations / 3)
      << window_iterations << " " << every_iterations;
  fs::remove_all(windows);
  fs::remove_all(every);
}

TEST(Substeps, AFlowAtAQuarterOfTheStepComesCloserToTheResolvedRun) {
  const fs::path resolved =
      run_variant("tube/flow_structure", "substeps_resolved", {6.25e-6, 1600});
  const fs::path coarse = run_variant("tube/flow_structure", "substeps_coarse", {1e-4, 100});
  const fs::path flow4 =
      run_variant("tube/flow_structure", "substeps_flow4", {1e-4, 100, 4, 1, "quadratic", true});
  const fs::path end_values =
      run_variant("tube/flow_structure", "substeps_end_values", {1e-4, 100, 4, 1, "linear", false});
  const auto reference = radial(resolved, 16);
  const double both = relative_l2(radial(coarse), reference);
  const double substepped = relative_l2(radial(flow4), reference);
  const double without_mean = relative_l2(radial(end_values), reference);
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
  // the interpolation's. Measured over 0.4 s: 3.78e-3, 2.09e-3, 1.21e-3 for steps of 0.02,
  // 0.01, 0.005 s (order 0.86, 0.79); linear 5.1e-3, 4.1e-3, 3.7e-3.
  std::vector<double> differences;
  for (const double delta_t : {0.02, 0.01, 0.005}) {
    const int steps = static_cast<int>(std::lround(0.4 / delta_t));
    const fs::path every =
        run_variant("tube/flow_ringmodel", "order_every", {delta_t / 4, 4 * steps}, 1e-11);
    const fs::path quadratic = run_variant("tube/flow_ringmodel", "order_quadratic",
                                           {delta_t, steps, 4, 1, "quadratic", false}, 1e-11);
    differences.push_back(relative_l2(radial(quadratic), radial(every, 4)));
    fs::remove_all(every);
    fs::remove_all(quadratic);
  }
  EXPECT_GT(differences[0] / differences[1], 1.5) << differences[0] << " " << differences[1];
  EXPECT_GT(differences[1] / differences[2], 1.5) << differences[1] << " " << differences[2];
  EXPECT_LT(differences[2], 2e-3);
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
