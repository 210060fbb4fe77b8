// A solver that crashes, hangs, returns NaN or is interrupted in the middle of `cocopp run`:
// the run stops with a message naming the solver, keeps the results written so far and leaves
// no process behind.
#include <gtest/gtest.h>

#include <fstream>

#include "tests/integration/run_helpers.hpp"

using namespace cocopp::testing;
namespace fs = std::filesystem;

namespace {

/// A case coupling cocopp-test-solver (as the flow side, 100 points like the tube) to the tube
/// structure, for 5 steps; `failure` configures the test solver.
fs::path failing_case(const std::string& tag, const std::string& failure,
                      const std::string& flow_settings = "") {
  const fs::path dir = copy_example("tube/flow_structure", tag);
  fs::create_directories(dir / "test_flow");
  write_text(dir / "test_flow" / "test_solver.in", "points 100\n" + failure + "\n");
  write_text(dir / "case.yaml", R"(settings: {delta_t: 1.0e-4, number_of_timesteps: 5}
coupled_solver:
  type: iqni
  omega: 0.05
  model: {type: ls}
  predictor: {type: linear}
  convergence_criterion: {type: relative_norm, tolerance: 1.0e-6}
solver_wrappers:
  - type: process
    name: flow
    working_directory: test_flow
    command: [)" + (fs::path(COCOPP_TEST_BIN_DIR) / "cocopp-test-solver").string() +
                                    "]\n" + flow_settings + R"(
  - {type: tube_structure, name: structure, working_directory: structure}
)");
  return dir;
}

/// Processes whose working directory lies inside `dir` (solvers left behind).
std::vector<std::string> processes_in(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& entry : fs::directory_iterator("/proc")) {
    const std::string pid = entry.path().filename();
    if (pid.find_first_not_of("0123456789") != std::string::npos) continue;
    std::error_code error;
    const fs::path cwd = fs::read_symlink(entry.path() / "cwd", error);
    if (!error && cwd.string().rfind(dir.string(), 0) == 0) found.push_back(pid);
  }
  return found;
}

/// The run stopped with `status` in step steps + 1 (at `iteration` where the coupler knows it),
/// for `reason`, after `steps` steps.
void expect_stopped(const fs::path& dir, const std::string& status, int steps,
                    const std::string& reason, int iteration = 0) {
  const auto summary = read_json(dir / "results" / "case.summary.json");
  EXPECT_EQ(summary["status"].get<std::string>(), status);
  EXPECT_EQ(summary["reason"].get<std::string>(), reason);
  EXPECT_EQ(summary["stopped_at"]["step"].get<int>(), steps + 1);
  if (iteration > 0)
    EXPECT_EQ(summary["stopped_at"]["iteration"].get<int>(), iteration);
  else
    EXPECT_TRUE(summary["stopped_at"]["iteration"].is_null());
  EXPECT_FALSE(summary["completed"].get<bool>());
  EXPECT_EQ(summary["steps_completed"].get<int>(), steps);
  // The steps before the failure are in the results file.
  EXPECT_EQ(read_dataset(dir / "results" / "case.h5", "steps/iterations").size(),
            std::size_t(steps));
  EXPECT_TRUE(processes_in(dir).empty()) << "a solver process was left behind";
}

}  // namespace

TEST(SolverFailures, CrashIsReportedWithTheLogTail) {
  const fs::path dir = failing_case("crash", "fail crash\nfail_step 3");
  const CommandResult run = run_cocopp("run " + (dir / "case.yaml").string());
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("solver 'flow'"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("signal 11"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("flow.log"), std::string::npos) << run.output;
  expect_stopped(dir, "solver_failed", 2, "solver failure in step 3");
  fs::remove_all(dir);
}

// The coupler sends a step's initialize_step, finalize_step and output_step to both solvers
// without waiting for each answer (they overlap): a failure in one of them is still reported
// in its own step, named after its request.
TEST(SolverFailures, AFailureInAnOverlappedStepRequestIsReportedInItsStep) {
  struct Case {
    std::string fail, request, expected;
  };
  for (const Case& c : {Case{"error", "output_step", "requested error at step 3"},
                        Case{"crash", "finalize_step", "signal 11"},
                        Case{"error", "initialize_step", "requested error at step 3"}}) {
    SCOPED_TRACE(c.fail + " in " + c.request);
    const fs::path dir = failing_case("overlapped_" + c.request,
                                      "fail " + c.fail + "\nfail_step 3\nfail_in " + c.request);
    const CommandResult run = run_cocopp("run " + (dir / "case.yaml").string());
    EXPECT_EQ(run.exit_code, 1) << run.output;
    EXPECT_NE(run.output.find(c.expected), std::string::npos) << run.output;
    EXPECT_NE(run.output.find("during " + c.request + " at step 3"), std::string::npos)
        << run.output;
    expect_stopped(dir, "solver_failed", 2, "solver failure in step 3");
    fs::remove_all(dir);
  }
}

TEST(SolverFailures, HangIsStoppedAfterTheTimeout) {
  const fs::path dir = failing_case("hang", "fail hang\nfail_step 2", "    timeout: 1");
  const CommandResult run = run_cocopp("run " + (dir / "case.yaml").string());
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("did not answer"), std::string::npos) << run.output;
  expect_stopped(dir, "solver_failed", 1, "solver failure in step 2");
  fs::remove_all(dir);
}

TEST(SolverFailures, NaNStopsTheRunAsDiverged) {
  const fs::path dir = failing_case("nan", "fail nan\nfail_step 4\nfail_iteration 2");
  const CommandResult run = run_cocopp("run " + (dir / "case.yaml").string());
  EXPECT_EQ(run.exit_code, 1) << run.output;
  EXPECT_NE(run.output.find("solver 'flow' returned a non-finite pressure at model part 'wall'"),
            std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("time step 4, coupling iteration 2"), std::string::npos) << run.output;
  expect_stopped(dir, "diverged", 3, "non-finite values in step 4, iteration 2", 2);
  fs::remove_all(dir);
}

TEST(SolverFailures, InterruptStopsTheSolversAndKeepsTheResults) {
  const fs::path dir = failing_case("interrupt", "fail hang\nfail_step 3");
  // SIGINT after 2 s, while the flow solver hangs in step 3 (its timeout is 600 s).
  const CommandResult run =
      run_command("timeout -s INT 2 " + (fs::path(COCOPP_TEST_BIN_DIR) / "cocopp").string() +
                  " run " + (dir / "case.yaml").string());
  EXPECT_NE(run.exit_code, 0) << run.output;
  EXPECT_NE(run.output.find("interrupted by signal 2"), std::string::npos) << run.output;
  expect_stopped(dir, "interrupted", 2, "interrupted in step 3");
  fs::remove_all(dir);
}
