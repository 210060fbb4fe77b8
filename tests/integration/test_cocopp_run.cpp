// `cocopp run` / `cocopp check` end to end, as a user runs them.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <thread>

#include "tests/integration/run_helpers.hpp"

using namespace cocopp::testing;
namespace fs = std::filesystem;

TEST(CocoppRun, FlowStructureTubeConvergesWithIqnIls) {
  const fs::path dir = copy_example("tube/flow_structure", "fs_iqni");
  const CommandResult run = run_cocopp("run " + (dir / "case.yaml").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  // Header, one progress line per step, summary.
  EXPECT_NE(run.output.find("coupled solver : iqni (omega 0.05, model ls)"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("step 100 / 100"), std::string::npos);
  // Issue 18: the residual as the relative criterion measures it, and the time left.
  EXPECT_NE(run.output.find("step   1 / 100  t = 0.0001     iterations  13  residual 3.170e-11  "
                            "(relative 5.62e-07)"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("  left "), std::string::npos);
  // Issue 51: a run of well under a second says how much of it is left in tenths, not "0 s".
  EXPECT_NE(run.output.find("  left 0."), std::string::npos) << run.output;
  EXPECT_EQ(run.output.find("  left 0 s"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("completed after 100 time steps"), std::string::npos);
  EXPECT_NE(run.output.find("per coupling iteration"), std::string::npos);

  const auto summary = read_json(dir / "results" / "case.summary.json");
  EXPECT_TRUE(summary["completed"].get<bool>());
  EXPECT_EQ(summary["steps_completed"].get<int>(), 100);
  const double average = summary["average_iterations"].get<double>();
  // With reuse of 10 steps IQN-ILS needs a few iterations per step (8 unstable modes).
  EXPECT_GT(average, 2.0);
  EXPECT_LT(average, 10.0);
  const auto iterations = read_dataset(dir / "results" / "case.h5", "steps/iterations");
  ASSERT_EQ(iterations.size(), 100u);
  const auto converged = read_dataset(dir / "results" / "case.h5", "steps/converged");
  for (double c : converged) EXPECT_EQ(c, 1.0);
  // The coupled-solver state at the end: the predictor's last two converged displacements
  // (linear predictor; 100 points x 3 components) and the reused IQN-ILS columns.
  const fs::path state = dir / "results" / "case.state.h5";
  EXPECT_NE(run.output.find("case.state.h5"), std::string::npos);
  EXPECT_EQ(read_dataset(state, "predictor/history").size(), 300u * 2u);
  const auto ages = read_dataset(state, "model/age");
  EXPECT_GT(ages.size(), 0u);
  EXPECT_EQ(read_dataset(state, "model/v").size(), 300u * ages.size());
  for (double age : ages) EXPECT_LE(age, 10.0);  // q = 10
  fs::remove_all(dir);
}

// Issue 18: `--verbose` shows every coupling iteration (a CFD step can take minutes).
TEST(CocoppRun, VerboseShowsEveryCouplingIteration) {
  const fs::path dir = copy_example("tube/flow_structure", "fs_verbose");
  edit(dir / "case.yaml", "number_of_timesteps: 100", "number_of_timesteps: 2");
  const CommandResult run = run_cocopp("run -v " + (dir / "case.yaml").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  for (int iteration = 1; iteration <= 13; ++iteration)
    EXPECT_NE(run.output.find(fmt::format("    step 1 iteration {:>3}  residual ", iteration)),
              std::string::npos)
        << iteration << run.output;
  EXPECT_EQ(run.output.find("    step 1 iteration  14"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("    step 1 iteration   1  residual 5.637e-05 (relative 1.00e+00)"),
            std::string::npos)
      << run.output;
  fs::remove_all(dir);
}

// settings.watchpoints: at a cell centre the nearest point's values, in the CSV file and in the
// results file alike, step by step.
TEST(CocoppRun, AWatchpointAtAPointHoldsThatPointsValues) {
  const fs::path dir = copy_example("tube/flow_structure", "fs_watchpoint");
  edit(dir / "case.yaml", "number_of_timesteps: 100",
       "number_of_timesteps: 20\n  watchpoints: [{name: mid, coordinates: [0, 0.005, 0.00025]}]");
  const CommandResult run = run_cocopp("run --quiet " + (dir / "case.yaml").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const fs::path results = dir / "results" / "case.h5";
  EXPECT_NE(run.output.find("watchpoint        : " + (dir / "results").string() +
                            "/case_watchpoint_mid.csv"),
            std::string::npos)
      << run.output;
  // Cell 50 of 100 is centred on z = 0.00025.
  const auto coordinates = read_dataset(results, "x/wall/coordinates");
  ASSERT_DOUBLE_EQ(coordinates[3 * 50 + 2], 0.00025);
  const auto displacement = read_dataset(results, "x/wall/displacement");
  const auto pressure = read_dataset(results, "y/wall/pressure");
  const auto watched_displacement = read_dataset(results, "watchpoints/mid/displacement");
  const auto watched_pressure = read_dataset(results, "watchpoints/mid/pressure");
  ASSERT_EQ(watched_pressure.size(), 20u);
  std::istringstream csv(read_text(dir / "results" / "case_watchpoint_mid.csv"));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line,
            "step,time,displacement_x,displacement_y,displacement_z,pressure,traction_x,"
            "traction_y,traction_z");
  for (int step = 1; step <= 20; ++step) {
    const std::size_t row = step - 1;
    EXPECT_EQ(watched_pressure[row], pressure[row * 100 + 50]) << step;
    EXPECT_EQ(watched_displacement[3 * row + 1], displacement[row * 300 + 3 * 50 + 1]) << step;
    ASSERT_TRUE(std::getline(csv, line));
    std::vector<double> columns;
    std::istringstream fields(line);
    for (std::string field; std::getline(fields, field, ',');) columns.push_back(std::stod(field));
    ASSERT_EQ(columns.size(), 9u) << line;
    EXPECT_EQ(columns[0], step);
    EXPECT_EQ(columns[3], watched_displacement[3 * row + 1]) << line;
    EXPECT_EQ(columns[5], watched_pressure[row]) << line;
  }
  EXPECT_FALSE(std::getline(csv, line)) << "one row per step";
  fs::remove_all(dir);
}

// Issue 18: solver-coupling convergence (CoCoNuT's criterion). Both tube solvers report whether
// the new input left them converged at their first iteration (the flow's Newton at its
// newtontol from the previous iterate, the wall equation below residual_atol); a step ends
// when both do, and the solution stays that of a tightly converged run.
TEST(CocoppRun, SolverCouplingConvergenceEndsAStepWhenBothTubeSolversAreConverged) {
  const fs::path reference = copy_example("tube/flow_structure", "fs_scc_reference");
  edit(reference / "case.yaml", "tolerance: 1.0e-6", "tolerance: 1.0e-12");
  edit(reference / "case.yaml", "maximum: 15", "maximum: 50");
  ASSERT_EQ(run_cocopp("run -q " + (reference / "case.yaml").string()).exit_code, 0);

  const fs::path dir = copy_example("tube/flow_structure", "fs_scc");
  use_solver_coupling_convergence(dir / "case.yaml");
  edit(dir / "flow" / "tube_flow.yaml", "newtontol: 1.0e-14", "newtontol: 1.0e-6");
  // Without residual_atol the wall cannot judge itself: the run stops at once, saying so.
  CommandResult run = run_cocopp("run -q " + (dir / "case.yaml").string());
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.output.find("solver 'structure' reported an error: solver-coupling convergence "
                            "needs residual_atol in the tube structure's input file"),
            std::string::npos)
      << run.output;
  edit(dir / "structure" / "tube_structure.yaml", "nu: 0.3", "nu: 0.3\nresidual_atol: 1.0e-8");
  run = run_cocopp("run " + (dir / "case.yaml").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("stop at ((solver_coupling_convergence(solver_index 0) and "
                            "solver_coupling_convergence(solver_index 1)) or iteration_limit 15)"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("(flow converged, structure converged)"), std::string::npos)
      << run.output;
  const fs::path results = dir / "results" / "case.h5";
  for (double converged : read_dataset(results, "steps/converged")) EXPECT_EQ(converged, 1.0);
  const auto iterations = read_dataset(results, "steps/iterations");
  double total = 0.0;
  for (double n : iterations) total += n;
  // Measured 3.68 per step (relative_norm 1e-6: 3.79), displacement within 3.4e-8 and pressure
  // within 2.4e-6 of the reference (relative 2-norms over the run; docs/coupling.md).
  EXPECT_LT(total / iterations.size(), 4.0);
  const fs::path tight = reference / "results" / "case.h5";
  EXPECT_LT(relative_difference(read_dataset(tight, "x/wall/displacement"),
                                read_dataset(results, "x/wall/displacement")),
            1e-7);
  EXPECT_LT(relative_difference(read_dataset(tight, "y/wall/pressure"),
                                read_dataset(results, "y/wall/pressure")),
            1e-5);
  fs::remove_all(dir);
  fs::remove_all(reference);
}

TEST(CocoppRun, FlowRingmodelTubeConverges) {
  const fs::path dir = copy_example("tube/flow_ringmodel", "fr_iqni");
  const CommandResult run = run_cocopp("run --quiet " + (dir / "case.yaml").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_EQ(run.output.find("step 1 /"), std::string::npos) << "--quiet prints no steps";
  const auto summary = read_json(dir / "results" / "case.summary.json");
  EXPECT_TRUE(summary["completed"].get<bool>());
  EXPECT_EQ(summary["steps_completed"].get<int>(), 100);
  fs::remove_all(dir);
}

TEST(CocoppRun, GaussSeidelIsReportedAsDivergingOnTheFlowStructureTube) {
  const fs::path dir = copy_example("tube/flow_structure", "fs_gs");
  write_text(dir / "case.yaml", R"(settings: {delta_t: 1.0e-4, number_of_timesteps: 100}
coupled_solver:
  type: gauss_seidel
  predictor: {type: linear}
  convergence_criterion:
    type: or
    criteria: [{type: relative_norm, tolerance: 1.0e-6}, {type: iteration_limit, maximum: 15}]
solver_wrappers:
  - {type: tube_flow, name: flow, working_directory: flow}
  - {type: tube_structure, name: structure, working_directory: structure}
)");
  const CommandResult run = run_cocopp("run " + (dir / "case.yaml").string());
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("diverged in time step 1"), std::string::npos) << run.output;
  const auto summary = read_json(dir / "results" / "case.summary.json");
  EXPECT_FALSE(summary["completed"].get<bool>());
  EXPECT_EQ(summary["status"].get<std::string>(), "diverged");
  // The results file stays readable: the layout is there, with no converged step.
  EXPECT_TRUE(read_dataset(dir / "results" / "case.h5", "steps/iterations").empty());
  // Issue 18: the step it stopped in keeps its residuals (5 iterations, growing by over 1e6),
  // and the plot script draws them.
  const auto norms = read_dataset(dir / "results" / "case.h5", "unfinished_step/residual_norms");
  ASSERT_EQ(norms.size(), 5u);
  EXPECT_GT(norms.back() / norms.front(), 1e6);
  const auto plot = dir / "results" / "case.png";
  EXPECT_EQ(std::system(("/usr/bin/python3 " + std::string(COCOPP_TEST_SOURCE_DIR) +
                         "/scripts/plot_results.py " + (dir / "results" / "case.h5").string() +
                         " -o " + plot.string() + " > /dev/null")
                            .c_str()),
            0);
  EXPECT_TRUE(fs::exists(plot));
  fs::remove_all(dir);
}

// The flow-structure tube run long after its pulse (1500 steps): a step's first residual is
// small and its iterations wander at the solvers' noise, creeping up for 10 iterations in step
// 1429 (to 3.5e-13, 6e-9 of the run's largest first residual). That is a stall, not a
// divergence: the run goes on to its end, and the step's warning says why it was not stopped.
TEST(CocoppRun, AResidualGrowingAtTheNoiseFloorIsNotADivergence) {
  const fs::path dir = copy_example("tube/flow_structure", "fs_long");
  edit(dir / "case.yaml", "number_of_timesteps: 100", "number_of_timesteps: 1500");
  for (const char* file : {"flow/tube_flow.yaml", "structure/tube_structure.yaml"})
    edit(dir / file, "interval: 10", "interval: 0");  // no VTK files
  const CommandResult run = run_cocopp("run -q " + (dir / "case.yaml").string());
  const auto summary = read_json(dir / "results" / "case.summary.json");
  EXPECT_EQ(summary["steps_completed"].get<int>(), 1500) << run.output;
  EXPECT_NE(summary["status"].get<std::string>(), "diverged");
  bool noted = false;
  for (const auto& warning : summary["warnings"])
    noted = noted || warning.get<std::string>().find("the solvers' noise, not a divergence") !=
                         std::string::npos;
  EXPECT_TRUE(noted) << summary["warnings"];
  fs::remove_all(dir);
}

// Issue 51: a run whose steps end at the iteration limit above the solvers' noise is
// "stalled" with exit code 3, which a script tells from success; steps at the limit with the
// residual at the noise (a relative criterion on a tube at rest: delta_t 1e4, the residual
// 1e-16 m) are no stall: "completed", exit 0, each step marked ~ and warned about.
TEST(CocoppRun, AStalledRunExitsWithThreeAndOneAtTheSolversNoiseWithZero) {
  const fs::path dir = copy_example("tube/flow_structure", "stalled");
  edit(dir / "case.yaml", "number_of_timesteps: 100", "number_of_timesteps: 5");
  edit(dir / "case.yaml", "maximum: 15", "maximum: 2");
  CommandResult run = run_cocopp("run " + (dir / "case.yaml").string());
  EXPECT_EQ(run.exit_code, 3) << run.output;
  EXPECT_NE(run.output.find("stalled after 5 time steps"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("5 of 5 steps at the iteration limit"), std::string::npos);
  auto summary = read_json(dir / "results" / "case.summary.json");
  EXPECT_EQ(summary["status"], "stalled");
  EXPECT_EQ(summary["steps_at_noise"].size(), 0u);

  edit(dir / "case.yaml", "maximum: 2", "maximum: 15");
  edit(dir / "case.yaml", "delta_t: 1.0e-4", "delta_t: 1.0e4");
  run = run_cocopp("run " + (dir / "case.yaml").string());
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("completed after 5 time steps"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("5 steps at the iteration limit with the residual at the solvers' "
                            "noise"),
            std::string::npos);
  EXPECT_NE(run.output.find("e-16~"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("warning: step 1: the iteration limit with the residual"),
            std::string::npos);
  summary = read_json(dir / "results" / "case.summary.json");
  EXPECT_EQ(summary["status"], "completed");
  EXPECT_EQ(summary["steps_at_noise"], nlohmann::json({1, 2, 3, 4, 5}));
  EXPECT_EQ(summary["unconverged_steps"].size(), 5u);
  fs::remove_all(dir);
}

// Issue 51: the plotting scripts behind one subcommand, from share/cocopp beside the
// executable (the build tree's as an install's): a results file drawn, the script's own help
// after the file, and a file of another kind refused with exit code 2.
TEST(CocoppRun, PlotDrawsAResultsFileWithTheInstalledScript) {
  const fs::path dir = copy_example("tube/flow_structure", "plot");
  edit(dir / "case.yaml", "number_of_timesteps: 100", "number_of_timesteps: 5");
  ASSERT_EQ(run_cocopp("run -q " + (dir / "case.yaml").string()).exit_code, 0);
  const fs::path results = dir / "results" / "case.h5", picture = dir / "picture.png";
  CommandResult plot = run_cocopp("plot " + results.string() + " -o " + picture.string());
  EXPECT_EQ(plot.exit_code, 0) << plot.output;
  ASSERT_TRUE(fs::exists(picture));
  EXPECT_GT(fs::file_size(picture), 10000u);
  plot = run_cocopp("plot " + results.string() + " --help");
  EXPECT_EQ(plot.exit_code, 0) << plot.output;
  EXPECT_NE(plot.output.find("--space-time"), std::string::npos) << plot.output;
  plot = run_cocopp("plot " + (dir / "case.yaml").string());
  EXPECT_EQ(plot.exit_code, 2);
  EXPECT_NE(plot.output.find("cocopp plot draws a results file"), std::string::npos);
  fs::remove_all(dir);
}

TEST(CocoppRun, YamlAndJsonGiveIdenticalRuns) {
  const fs::path yaml_dir = copy_example("tube/flow_structure", "fs_yaml");
  const fs::path json_dir = copy_example("tube/flow_structure", "fs_json");
  ASSERT_EQ(run_cocopp("run -q " + (yaml_dir / "case.yaml").string()).exit_code, 0);
  ASSERT_EQ(run_cocopp("run -q " + (json_dir / "case.json").string()).exit_code, 0);
  for (const char* dataset :
       {"steps/iterations", "residuals/norms", "x/wall/displacement", "y/wall/pressure"}) {
    const auto from_yaml = read_dataset(yaml_dir / "results" / "case.h5", dataset);
    const auto from_json = read_dataset(json_dir / "results" / "case.h5", dataset);
    ASSERT_FALSE(from_yaml.empty()) << dataset;
    EXPECT_EQ(from_yaml, from_json) << dataset;  // bit for bit
  }
  fs::remove_all(yaml_dir);
  fs::remove_all(json_dir);
}

TEST(CocoppCheck, ValidCaseIsAccepted) {
  const fs::path dir = copy_example("tube/flow_structure", "check_ok");
  const CommandResult check = run_cocopp("check " + (dir / "case.yaml").string());
  EXPECT_EQ(check.exit_code, 0) << check.output;
  EXPECT_NE(check.output.find("OK"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "results")) << "check must not run anything";
  fs::remove_all(dir);
}

TEST(CocoppCheck, TypoInAKeyNamesFileLineAndSuggestion) {
  const fs::path dir = copy_example("tube/flow_structure", "check_typo");
  edit(dir / "case.yaml", "  omega: 0.05", "  omgea: 0.05");
  const CommandResult check = run_cocopp("check " + (dir / "case.yaml").string());
  EXPECT_EQ(check.exit_code, 2);
  // The key is on line 11, column 3 of the example.
  EXPECT_NE(check.output.find("case.yaml:11:3: unknown key 'coupled_solver.omgea'; did you mean "
                              "'omega'?"),
            std::string::npos)
      << check.output;
  fs::remove_all(dir);
}

TEST(CocoppCheck, UnknownTypeWrongTypeAndRange) {
  const fs::path dir = copy_example("tube/flow_structure", "check_types");
  const fs::path file = dir / "case.yaml";
  const std::string original = read_text(file);

  edit(file, "type: linear", "type: lineair");
  auto check = run_cocopp("check " + file.string());
  EXPECT_EQ(check.exit_code, 2);
  EXPECT_NE(check.output.find("unknown predictor 'lineair'; did you mean 'linear'?"),
            std::string::npos)
      << check.output;

  write_text(file, original);
  edit(file, "number_of_timesteps: 100", "number_of_timesteps: many");
  check = run_cocopp("check " + file.string());
  EXPECT_NE(check.output.find("'settings.number_of_timesteps': expected an integer, got 'many'"),
            std::string::npos)
      << check.output;

  write_text(file, original);
  edit(file, "delta_t: 1.0e-4", "delta_t: -1.0e-4");
  check = run_cocopp("check " + file.string());
  EXPECT_NE(check.output.find("case.yaml:6:"), std::string::npos) << check.output;
  EXPECT_NE(check.output.find("'settings.delta_t': must be > 0, got -0.0001"), std::string::npos)
      << check.output;

  write_text(file, original);
  edit(file, "    working_directory: structure\n", "");
  check = run_cocopp("check " + file.string());
  EXPECT_NE(check.output.find("missing required key 'solver_wrappers[1].working_directory'"),
            std::string::npos)
      << check.output;
  fs::remove_all(dir);
}

namespace {
/// `cocopp check` of `file` with its `original` text, `from` replaced by `to`.
CommandResult check_edited(const fs::path& file, const std::string& original,
                           const std::string& from, const std::string& to) {
  write_text(file, original);
  edit(file, from, to);
  return run_cocopp("check " + file.string());
}
}  // namespace

// Numbers `check` used to pass that broke the run (issue 17): an end time beyond the int
// range of steps ("completed after 0 time steps"), a start step near it (negative step
// numbers), a timeout whose deadline overflows the clock; and two solvers in one working
// directory, which share a channel.
TEST(CocoppCheck, NumbersThatWouldBreakTheRunAndASharedWorkingDirectory) {
  const fs::path dir = copy_example("tube/flow_structure", "check_ranges");
  const fs::path file = dir / "case.yaml";
  const std::string original = read_text(file);
  auto expect_error = [&](const std::string& from, const std::string& to,
                          const std::string& message) {
    const auto check = check_edited(file, original, from, to);
    EXPECT_EQ(check.exit_code, 2) << check.output;
    EXPECT_NE(check.output.find(message), std::string::npos) << check.output;
  };
  expect_error("number_of_timesteps: 100", "number_of_timestep: 100",
               "give exactly one of 'number_of_timesteps' and 'end_time'; is "
               "'number_of_timestep' (line 7) a misspelling of it?");
  expect_error("number_of_timesteps: 100", "end_time: 1.0e+6",
               "'settings.end_time': is 1e+10 time steps of delta_t after the start: at most "
               "1000000000 are possible");
  expect_error("number_of_timesteps: 100", "number_of_timesteps: 100\n  timestep_start: 2147483000",
               "'settings.timestep_start'");
  expect_error("    working_directory: structure\n",
               "    working_directory: structure\n    timeout: 1.0e+10\n",
               "'solver_wrappers[1].timeout': must be in (0, 10000000], got 10000000000");
  expect_error("    working_directory: structure\n", "    working_directory: flow/\n",
               "'solver_wrappers[1].working_directory': is also another solver's");
  // The same folder written another way: absolute, through its parent, through a link.
  expect_error("    working_directory: structure\n",
               "    working_directory: " + (dir / "flow").string() + "\n",
               "'solver_wrappers[1].working_directory': is also another solver's");
  expect_error("    working_directory: structure\n",
               "    working_directory: ../" + dir.filename().string() + "/flow\n",
               "'solver_wrappers[1].working_directory': is also another solver's");
  fs::create_directory_symlink(dir / "flow", dir / "flow_link");
  expect_error("    working_directory: structure\n", "    working_directory: flow_link\n",
               "'solver_wrappers[1].working_directory': is also another solver's");
  expect_error("    working_directory: structure\n", "    working_directory: ''\n",
               "'solver_wrappers[1].working_directory': is empty");
  fs::remove_all(dir);
}

TEST(CocoppCli, HelpDocumentsTheCommands) {
  for (const char* arguments : {"--help", "run --help", "check --help"}) {
    const CommandResult help = run_cocopp(arguments);
    EXPECT_EQ(help.exit_code, 0) << arguments;
    EXPECT_NE(help.output.find("case"), std::string::npos) << help.output;
  }
  const CommandResult export_help = run_cocopp("export-vtk --help");
  EXPECT_EQ(export_help.exit_code, 0);
  EXPECT_NE(export_help.output.find("ParaView"), std::string::npos) << export_help.output;
  // A file that is not a results file: exit 1 with the file named.
  const CommandResult not_results = run_cocopp("export-vtk " + std::string(COCOPP_TEST_SOURCE_DIR) +
                                               "/examples/tube/flow_structure/case.yaml");
  EXPECT_EQ(not_results.exit_code, 1) << not_results.output;
  EXPECT_NE(not_results.output.find("error: "), std::string::npos) << not_results.output;
  EXPECT_NE(not_results.output.find("case.yaml"), std::string::npos) << not_results.output;
  const CommandResult components = run_cocopp("components");
  EXPECT_NE(components.output.find("gauss_seidel"), std::string::npos) << components.output;
  EXPECT_NE(components.output.find("tube_flow"), std::string::npos) << components.output;
}

// The same tube with a 73-cell structure behind a `mapped` wrapper (linear in z) gives the
// flow pressure of the matching 100-cell run up to the structure's coarser discretisation.
TEST(CocoppRun, MappedTubeWithNonMatchingMeshesAgreesWithTheMatchingRun) {
  const fs::path matching = copy_example("tube/flow_structure", "fs_matching");
  const fs::path mapped = copy_example("tube/flow_structure_mapped", "fs_mapped");
  ASSERT_EQ(run_cocopp("run -q " + (matching / "case.yaml").string()).exit_code, 0);
  const CommandResult run = run_cocopp("run -q " + (mapped / "case.yaml").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("structure mapped onto"), std::string::npos) << run.output;
  // Issue 18: the solver inside the mapped wrapper carries the case's name (it logged to
  // tube_structure.log, after its type).
  EXPECT_TRUE(fs::exists(mapped / "structure" / "structure.log"));
  EXPECT_FALSE(fs::exists(mapped / "structure" / "tube_structure.log"));
  // The quality report: the flow's end points lie beyond the structure's, so they fall back.
  EXPECT_NE(run.output.find("structure output mapper, wall -> wall"), std::string::npos)
      << run.output;
  const auto reference = read_dataset(matching / "results" / "case.h5", "y/wall/pressure");
  const auto pressure = read_dataset(mapped / "results" / "case.h5", "y/wall/pressure");
  ASSERT_EQ(pressure.size(), reference.size());
  double difference = 0.0, norm = 0.0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    difference += (pressure[i] - reference[i]) * (pressure[i] - reference[i]);
    norm += reference[i] * reference[i];
  }
  // Measured 0.46 %: the 73-cell structure's discretisation error, not the mapping's.
  EXPECT_LT(std::sqrt(difference / norm), 0.02);
  const auto summary = read_json(mapped / "results" / "case.summary.json");
  EXPECT_TRUE(summary["completed"].get<bool>());
  fs::remove_all(matching);
  fs::remove_all(mapped);
}

// Issue 17, defect 1: a second run of a case while the first runs stops before it touches any
// file (the results, the summary, the solvers' channels) and names the first run's pid; the
// first run completes with a whole results file.
TEST(CocoppRun, ASecondRunOfARunningCaseStopsAndLeavesTheFirstAlone) {
  const fs::path dir = copy_example("tube/flow_structure", "second_run");
  edit(dir / "case.yaml", "number_of_timesteps: 100", "number_of_timesteps: 3000");
  const fs::path log = dir / "first.log";
  run_command("(" + (fs::path(COCOPP_TEST_BIN_DIR) / "cocopp").string() + " run " +
              (dir / "case.yaml").string() + " > " + log.string() + " 2>&1; echo \"exit $?\" >> " +
              log.string() + ") > /dev/null 2>&1 &");
  const auto wait_for = [&](const std::string& text) {
    for (int i = 0; i < 3000 && read_text(log).find(text) == std::string::npos; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return read_text(log).find(text) != std::string::npos;
  };
  ASSERT_TRUE(wait_for("step  100 / 3000")) << read_text(log);
  const auto summary_before = fs::last_write_time(dir / "results" / "case.h5");
  const CommandResult second = run_cocopp("run " + (dir / "case.yaml").string());
  EXPECT_EQ(second.exit_code, 1) << second.output;
  const auto pid_at = second.output.find("another cocopp run (pid ");
  ASSERT_NE(pid_at, std::string::npos) << second.output;
  const std::string pid = std::to_string(std::stoi(second.output.substr(pid_at + 24)));
  EXPECT_NE(read_text("/proc/" + pid + "/cmdline").find("cocopp"), std::string::npos);
  EXPECT_NE(second.output.find("case.lock"), std::string::npos) << second.output;
  EXPECT_EQ(second.output.find("time steps"), std::string::npos) << "no header: nothing started";
  ASSERT_TRUE(wait_for("exit ")) << read_text(log);
  // (Long after the pulse some steps end at the iteration limit at the solvers' noise: no
  // stall, "completed", exit code 0.)
  EXPECT_NE(read_text(log).find("completed after 3000 time steps"), std::string::npos)
      << read_text(log).substr(read_text(log).size() > 2000 ? read_text(log).size() - 2000 : 0);
  EXPECT_NE(read_text(log).find("exit 0"), std::string::npos);
  EXPECT_EQ(read_dataset(dir / "results" / "case.h5", "steps/step").size(), 3000u);
  EXPECT_GE(fs::last_write_time(dir / "results" / "case.h5"), summary_before);
  EXPECT_EQ(read_json(dir / "results" / "case.summary.json")["steps_completed"].get<int>(), 3000);
  // Ended, the first run holds nothing, and leaves no lock file: the case runs again.
  EXPECT_FALSE(fs::exists(dir / "results" / "case.lock"));
  EXPECT_FALSE(fs::exists(dir / "flow" / ".cocopp.lock"));
  edit(dir / "case.yaml", "number_of_timesteps: 3000", "number_of_timesteps: 5");
  EXPECT_EQ(run_cocopp("run --quiet " + (dir / "case.yaml").string()).exit_code, 0);
  EXPECT_FALSE(fs::exists(dir / "results" / "case.lock"));
  fs::remove_all(dir);
}

// Issue 17, defect 2: a results location that cannot be used is a clean error (exit 1) before
// any solver starts, never an abort.
TEST(CocoppRun, AResultsLocationThatCannotBeUsedStopsTheRunBeforeTheSolversStart) {
  const fs::path dir = copy_example("tube/flow_structure", "results_location");
  const auto expect_clean_error = [&](const std::string& message) {
    const CommandResult run = run_cocopp("run " + (dir / "case.yaml").string());
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_NE(run.output.find("error: "), std::string::npos) << run.output;
    EXPECT_NE(run.output.find(message), std::string::npos) << run.output;
    EXPECT_FALSE(fs::exists(dir / "flow" / "flow.log")) << "a solver was started";
  };
  write_text(dir / "results", "a file where the results directory should be\n");
  expect_clean_error("cannot use the directory " + (dir / "results").string() +
                     ": it is not a directory");
  fs::remove(dir / "results");
  // Issue 17, defect 9: filesystem errors in words, at the key (they were raw "filesystem
  // error: status: ..." texts).
  const std::string original = read_text(dir / "case.yaml");
  edit(dir / "case.yaml", "number_of_timesteps: 100",
       "number_of_timesteps: 100\n  results_directory: " + std::string(300, 'x'));
  expect_clean_error("case.yaml:8:22: 'settings.results_directory': cannot use the directory");
  expect_clean_error("has a name longer than the file system allows");
  write_text(dir / "case.yaml", original);
  fs::create_symlink("loop_b", dir / "loop_a");
  fs::create_symlink("loop_a", dir / "loop_b");
  edit(dir / "case.yaml", "number_of_timesteps: 100",
       "number_of_timesteps: 100\n  results_directory: loop_a/results");
  expect_clean_error("is a loop of symbolic links");
  // A directory that cannot be created (under /proc, where even root cannot) is named at its
  // key too; so is a log file's folder under a file, already by check.
  write_text(dir / "case.yaml", original);
  edit(dir / "case.yaml", "number_of_timesteps: 100",
       "number_of_timesteps: 100\n  results_directory: /proc/none/results");
  expect_clean_error(
      "case.yaml:8:22: 'settings.results_directory': cannot create the directory "
      "/proc/none/results");
  write_text(dir / "case.yaml", original);
  edit(dir / "case.yaml", "    working_directory: flow ",
       "    log_file: ../case.yaml/flow.log\n    working_directory: flow ");
  const CommandResult check = run_cocopp("check " + (dir / "case.yaml").string());
  EXPECT_EQ(check.exit_code, 2) << check.output;
  EXPECT_NE(check.output.find("solver 'flow': the log file's folder"), std::string::npos)
      << check.output;
  EXPECT_NE(check.output.find("case.yaml is not a directory"), std::string::npos) << check.output;
  fs::remove_all(dir);
}

// Issue 17, defects 9 and 10: paths from the case that cannot be used, and names that would
// be paths, are errors at their key in words, from `check` as from `run`.
TEST(CocoppCheck, PathsThatCannotBeUsedAreNamedInWordsAtTheirKey) {
  const fs::path dir = copy_example("tube/flow_structure", "check_paths");
  const fs::path file = dir / "case.yaml";
  const std::string original = read_text(file);
  fs::create_symlink("loop_b", dir / "loop_a");
  fs::create_symlink("loop_a", dir / "loop_b");
  auto expect_error = [&](const std::string& from, const std::string& to,
                          const std::string& message) {
    const auto check = check_edited(file, original, from, to);
    EXPECT_EQ(check.exit_code, 2) << check.output;
    EXPECT_NE(check.output.find(message), std::string::npos) << check.output;
    EXPECT_EQ(check.output.find("filesystem error"), std::string::npos) << check.output;
  };
  expect_error("working_directory: flow ", "working_directory: loop_a/flow ",
               "case.yaml:28:24: solver 'flow': working directory " +
                   (dir / "loop_a/flow").string() + " is a loop of symbolic links");
  expect_error("working_directory: flow ", "working_directory: " + std::string(300, 'y') + " ",
               "has a name longer than the file system allows");
  expect_error("working_directory: flow ", "working_directory: flow/tube_flow.yaml ",
               "is not a directory");
  expect_error("number_of_timesteps: 100", "number_of_timesteps: 100\n  results_directory: loop_a",
               "'settings.results_directory': cannot use the directory");
  expect_error("number_of_timesteps: 100", "number_of_timesteps: 100\n  results_name: ../../x",
               "'settings.results_name': '../../x' is not a plain name");
  fs::remove_all(dir);
}

// Issue 18: a typo in a built-in solver's own input file passed `check` and failed at `run`.
TEST(CocoppCheck, ABuiltInSolversInputFileIsReadAsTheSolverReadsIt) {
  const fs::path dir = copy_example("tube/flow_structure", "check_solver_input");
  edit(dir / "flow" / "tube_flow.yaml", "cells: 100", "cels: 100");
  const auto check = run_cocopp("check " + (dir / "case.yaml").string());
  EXPECT_EQ(check.exit_code, 2) << check.output;
  EXPECT_NE(check.output.find("tube_flow.yaml:5:1: missing required key 'cells'; is 'cels' "
                              "(line 7) a misspelling of it?"),
            std::string::npos)
      << check.output;
  fs::remove_all(dir);
}

// Issue 17, defect 9: command-line errors exit with the documented code 2 (CLI11's own were
// 105 and 106); --help and --version with 0.
TEST(CocoppRun, CommandLineErrorsExitWithTwo) {
  for (const std::string arguments :
       {"run", "run /nonexistent/case.yaml", "run --no-such-flag x.yaml", "frobnicate", ""}) {
    const CommandResult run = run_cocopp(arguments);
    EXPECT_EQ(run.exit_code, 2) << "cocopp " << arguments << ": " << run.output;
  }
  for (const std::string arguments : {"--help", "run --help", "--version"})
    EXPECT_EQ(run_cocopp(arguments).exit_code, 0) << arguments;
}

// Issue 17, defect 10: links planted at the names cocopp writes never make it write their
// targets: a results file that is a link is refused before anything starts, a solver log
// that is a link stops the solver's start, a link at the state file's temporary name is
// replaced.
TEST(CocoppRun, LinksPlantedAtItsFileNamesNeverMakeItWriteTheirTargets) {
  const fs::path dir = copy_example("tube/flow_structure", "planted_links");
  edit(dir / "case.yaml", "number_of_timesteps: 100", "number_of_timesteps: 3");
  const fs::path target = dir / "precious.txt";
  write_text(target, "keep me\n");
  fs::create_directories(dir / "results");
  const auto run = [&] { return run_cocopp("run --quiet " + (dir / "case.yaml").string()); };

  fs::create_symlink(target, dir / "results" / "case.h5");
  CommandResult result = run();
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("case.h5 is a symbolic link"), std::string::npos) << result.output;
  fs::remove(dir / "results" / "case.h5");

  fs::create_symlink(target, dir / "flow" / "flow.log");
  result = run();
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("cannot open the log file"), std::string::npos) << result.output;
  fs::remove(dir / "flow" / "flow.log");

  fs::create_symlink(target, dir / "results" / "case.state.h5.writing");
  result = run();
  EXPECT_EQ(result.exit_code, 0) << result.output;
  EXPECT_FALSE(fs::is_symlink(dir / "results" / "case.state.h5"));
  EXPECT_EQ(read_text(target), "keep me\n");
  fs::remove_all(dir);
}
