// Restart of a coupled run (`cocopp run --restart`, settings.timestep_start) on the tube: a run
// stopped after a saved step and continued equals the uninterrupted run bit for bit, and every
// way a restart cannot work is a clear error.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "tests/integration/run_helpers.hpp"

using namespace cocopp::testing;
namespace fs = std::filesystem;

namespace {

/// Everything a run computes, per step: iterations, residual norms, x and y.
const std::vector<std::string> kComputed = {
    "steps/step",       "steps/iterations",    "steps/converged", "residuals/norms",
    "residuals/offset", "x/wall/displacement", "y/wall/pressure", "y/wall/traction"};

/// The same results, bit for bit; and where the run had the watchpoint of
/// flow_structure_case(), its values in the results file and its CSV file, every step once.
void expect_same_results(const fs::path& expected, const fs::path& actual) {
  std::vector<std::string> computed = kComputed;
  const fs::path csv = "case_watchpoint_middle.csv";
  if (fs::exists(expected.parent_path() / csv)) {
    computed.insert(computed.end(),
                    {"watchpoints/middle/displacement", "watchpoints/middle/pressure"});
    EXPECT_EQ(read_text(expected.parent_path() / csv), read_text(actual.parent_path() / csv));
  }
  for (const auto& name : computed) {
    const auto a = read_dataset(expected, name);
    const auto b = read_dataset(actual, name);
    ASSERT_EQ(a.size(), b.size()) << name;
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.size(); ++i) differing += a[i] != b[i];  // bit for bit
    EXPECT_EQ(differing, 0u) << name << ": values that differ from the uninterrupted run";
  }
}

/// `side_by_side`: the solvers side by side (scheme parallel), whose state holds x and y and the
/// residual-sum weights.
std::string flow_structure_case(int steps, int state_interval, bool side_by_side = false) {
  return R"(settings: {delta_t: 1.0e-4, number_of_timesteps: )" + std::to_string(steps) +
         ", state_interval: " + std::to_string(state_interval) + R"(,
           watchpoints: [{name: middle, coordinates: [0, 0.005, 0.00025]}]}
coupled_solver:
  type: iqni
  omega: 0.05
  model: {type: ls, q: 10, min_significant: 1.0e-12}
  predictor: {type: linear}
)" +
         (side_by_side ? R"(  scheme: parallel
  load_criterion: {type: absolute_norm, tolerance: 1.0e-4}
  convergence_criterion:
    type: or
    criteria: [{type: absolute_norm, tolerance: 1.0e-11}, {type: iteration_limit, maximum: 50}]
)"
                       : R"(  convergence_criterion:
    type: or
    criteria: [{type: relative_norm, tolerance: 1.0e-6}, {type: iteration_limit, maximum: 15}]
)") + R"(solver_wrappers:
  - {type: tube_flow, name: flow, working_directory: flow}
  - {type: tube_structure, name: structure, working_directory: structure}
)";
}

class Restart : public ::testing::Test {
 protected:
  void SetUp() override {
    reference_ = copy_example("tube/flow_structure", "restart_reference");
    dir_ = copy_example("tube/flow_structure", "restart");
  }
  void TearDown() override {
    if (HasFailure()) return;  // kept for inspection
    fs::remove_all(reference_);
    fs::remove_all(dir_);
  }
  /// The uninterrupted run of `steps` steps, in the reference directory.
  void run_reference(int steps, bool side_by_side = false) {
    write_text(reference_ / "case.yaml", flow_structure_case(steps, 0, side_by_side));
    const CommandResult run = run_cocopp("run --quiet " + (reference_ / "case.yaml").string());
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  fs::path results(const fs::path& dir) const { return dir / "results" / "case.h5"; }
  fs::path reference_, dir_;
};

// Run to step 50, then raise number_of_timesteps to 100 and continue with --restart.
TEST_F(Restart, ARunContinuedAfterItsEndEqualsTheUninterruptedRun) {
  run_reference(100);
  write_text(dir_ / "case.yaml", flow_structure_case(50, 0));
  const CommandResult first = run_cocopp("run --quiet " + (dir_ / "case.yaml").string());
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_TRUE(fs::exists(dir_ / "flow" / "restart" / "tube_flow_000050.restart"));
  EXPECT_TRUE(fs::exists(dir_ / "structure" / "restart" / "tube_structure_000050.restart"));

  write_text(dir_ / "case.yaml", flow_structure_case(100, 0));
  const CommandResult second = run_cocopp("run --restart " + (dir_ / "case.yaml").string());
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_NE(second.output.find("restart        : after step 50"), std::string::npos)
      << second.output;
  EXPECT_NE(second.output.find("step  51 / 100"), std::string::npos) << second.output;
  EXPECT_NE(second.output.find("completed after 50 time steps"), std::string::npos);
  expect_same_results(results(reference_), results(dir_));
  const auto summary = read_json(dir_ / "results" / "case.summary.json");
  EXPECT_TRUE(summary["restarted"].get<bool>());
  EXPECT_EQ(summary["timestep_start"].get<int>(), 50);
  // The same through settings.timestep_start, which names the step to continue after.
  write_text(dir_ / "case.yaml", flow_structure_case(50, 0));
  const CommandResult rerun = run_cocopp("run --quiet " + (dir_ / "case.yaml").string());
  ASSERT_EQ(rerun.exit_code, 0) << rerun.output;
  edit(dir_ / "case.yaml", "number_of_timesteps: 50,",
       "timestep_start: 50, number_of_timesteps: 50,");
  const CommandResult by_key = run_cocopp("run --quiet " + (dir_ / "case.yaml").string());
  ASSERT_EQ(by_key.exit_code, 0) << by_key.output;
  expect_same_results(results(reference_), results(dir_));
}

// Side by side the state holds x and y (the predictor's history of both, the secant columns of
// the stacked unknown) and the residual-sum weights: the restarted run is the same bit for bit.
TEST_F(Restart, ASideBySideRunContinuesAsTheUninterruptedOne) {
  run_reference(100, true);
  write_text(dir_ / "case.yaml", flow_structure_case(50, 0, true));
  const CommandResult first = run_cocopp("run --quiet " + (dir_ / "case.yaml").string());
  ASSERT_EQ(first.exit_code, 0) << first.output;
  write_text(dir_ / "case.yaml", flow_structure_case(100, 0, true));
  const CommandResult second = run_cocopp("run --restart " + (dir_ / "case.yaml").string());
  ASSERT_EQ(second.exit_code, 0) << second.output;
  expect_same_results(results(reference_), results(dir_));
  // A serial run cannot continue it: the saved unknown is x and y.
  write_text(dir_ / "case.yaml", flow_structure_case(120, 0));
  const CommandResult serial = run_cocopp("run --restart " + (dir_ / "case.yaml").string());
  EXPECT_NE(serial.exit_code, 0);
  EXPECT_NE(serial.output.find("continues with the same scheme"), std::string::npos)
      << serial.output;
  // A fresh coupled solver may: the serial one takes the displacement's history.
  const CommandResult fresh =
      run_cocopp("run --restart --fresh-coupling " + (dir_ / "case.yaml").string());
  EXPECT_EQ(fresh.exit_code, 0) << fresh.output;
  EXPECT_NE(fresh.output.find("step 120 / 120"), std::string::npos) << fresh.output;
  // And side by side after serial (the bench's start_from_state): the loads' history starts
  // at what the flow reports after its restart.
  write_text(dir_ / "case.yaml", flow_structure_case(130, 0, true));
  const CommandResult back =
      run_cocopp("run --restart --fresh-coupling " + (dir_ / "case.yaml").string());
  EXPECT_EQ(back.exit_code, 0) << back.output;
  EXPECT_NE(back.output.find("step 130 / 130"), std::string::npos) << back.output;
}

// A run killed (SIGKILL, no chance to write anything) somewhere after step 57, with the state
// saved every 10 steps: --restart continues after the last saved step, drops the results the
// killed run wrote after it, and ends with the uninterrupted run's results.
TEST_F(Restart, AKilledRunContinuesFromItsLastSavedState) {
  constexpr int kSteps = 300;
  run_reference(kSteps);
  write_text(dir_ / "case.yaml", flow_structure_case(kSteps, 10));
  const fs::path log = dir_ / "first.log";
  const CommandResult started =
      run_command((fs::path(COCOPP_TEST_BIN_DIR) / "cocopp").string() + " run " +
                  (dir_ / "case.yaml").string() + " > " + log.string() + " 2>&1 & echo $!");
  const pid_t pid = std::stoi(started.output);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (read_text(log).find(" 57 / 300") == std::string::npos &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ::kill(pid, SIGKILL);
  const std::string first = read_text(log);
  ASSERT_NE(first.find(" 57 / 300"), std::string::npos) << first;
  ASSERT_EQ(first.find("completed after"), std::string::npos)
      << "the run ended before it was killed: nothing tested\n"
      << first;
  for (int i = 0; i < 100 && run_command("kill -0 " + std::to_string(pid)).exit_code == 0; ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));

  const CommandResult second = run_cocopp("run --restart " + (dir_ / "case.yaml").string());
  ASSERT_EQ(second.exit_code, 0) << second.output;
  const auto restart_line = second.output.find("restart        : after step ");
  ASSERT_NE(restart_line, std::string::npos) << second.output;
  const int saved = std::stoi(second.output.substr(restart_line + 28));
  EXPECT_GE(saved, 50);
  EXPECT_EQ(saved % 10, 0);
  expect_same_results(results(reference_), results(dir_));
  EXPECT_EQ(read_dataset(results(dir_), "steps/step").size(), std::size_t(kSteps));
}

// IQN-ILSM: the surrogate's own solvers save and restart with the case's, its coupled solver
// goes through the state file (surrogate/...): 50 + 50 steps equal 100 bit for bit.
TEST_F(Restart, IqnIlsmRestartsItsSurrogateToo) {
  const fs::path reference = copy_example("tube/surrogate", "restart_surrogate_reference");
  const fs::path split = copy_example("tube/surrogate", "restart_surrogate");
  const CommandResult whole = run_cocopp("run --quiet " + (reference / "case.yaml").string());
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  edit(split / "case.yaml", "number_of_timesteps: 100", "number_of_timesteps: 50");
  const CommandResult first = run_cocopp("run --quiet " + (split / "case.yaml").string());
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_TRUE(fs::exists(split / "surrogate_flow" / "restart" / "tube_flow_000050.restart"));
  edit(split / "case.yaml", "number_of_timesteps: 50", "number_of_timesteps: 100");
  const CommandResult second = run_cocopp("run --restart " + (split / "case.yaml").string());
  ASSERT_EQ(second.exit_code, 0) << second.output;
  expect_same_results(results(reference), results(split));
  if (HasFailure()) return;
  fs::remove_all(reference);
  fs::remove_all(split);
}

TEST_F(Restart, WhatCannotBeRestartedIsAClearError) {
  write_text(dir_ / "case.yaml", flow_structure_case(20, 0));
  const std::string case_file = (dir_ / "case.yaml").string();
  const auto expect_error = [&](const std::string& arguments, int exit_code,
                                const std::string& message) {
    const CommandResult run = run_cocopp(arguments + " " + case_file);
    EXPECT_EQ(run.exit_code, exit_code) << run.output;
    EXPECT_NE(run.output.find(message), std::string::npos) << run.output;
  };
  // Nothing saved yet.
  expect_error("run --restart", 2, "cannot restart: there is no state file");
  expect_error("run --restart", 2, "run the case without --restart first");
  edit(dir_ / "case.yaml", "number_of_timesteps: 20,",
       "timestep_start: 10, number_of_timesteps: 10,");
  expect_error("check", 2, "settings.timestep_start is 10");
  expect_error("run", 2, "set timestep_start to 0 to run from the start");

  // Saved at step 20, the case's end.
  write_text(dir_ / "case.yaml", flow_structure_case(20, 0));
  ASSERT_EQ(run_cocopp("run --quiet " + case_file).exit_code, 0);
  expect_error("run --restart", 2, "nothing to restart: the state file");
  expect_error("run --restart", 2, "raise settings.number_of_timesteps or settings.end_time");
  edit(dir_ / "case.yaml", "number_of_timesteps: 20,",
       "timestep_start: 10, number_of_timesteps: 20,");
  expect_error("run", 2, "holds step 20");
  expect_error("run", 2, "set timestep_start to 20, or run with --restart");

  // A solver without its restart file: the solver says which file it misses.
  write_text(dir_ / "case.yaml", flow_structure_case(30, 0));
  fs::remove_all(dir_ / "structure" / "restart");
  const CommandResult run = run_cocopp("run --restart " + case_file);
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("restart/tube_structure_000020.restart: not found"), std::string::npos)
      << run.output;
  // The results of the first run are still there, whole.
  EXPECT_EQ(read_dataset(results(dir_), "steps/step").size(), 20u);
}

}  // namespace
