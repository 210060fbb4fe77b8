// RunSummary: the JSON content and the atomic write.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "coupler/results/run_summary.hpp"
#include "tests/unit/coupler/results/results_fixture.hpp"

namespace cocopp::test {
namespace {

using nlohmann::json;

RunOutcome outcome(RunStatus status, const std::string& message, const std::string& reason,
                   int step = 0) {
  RunOutcome o;
  o.status = status;
  o.message = message;
  o.reason = reason;
  o.step = step;
  return o;
}

RunSummary summary_of(int steps) {
  RunSummary summary(make_run(steps));
  for (int step = 1; step <= steps; ++step) summary.add_step(make_record(step));
  return summary;
}

json read_json(const std::filesystem::path& file) {
  std::ifstream in(file);
  return json::parse(in);
}

std::vector<std::string> directory_entries(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(RunSummary, ContentAfterFinish) {
  RunSummary summary = summary_of(3);
  summary.finish(outcome(RunStatus::kStalled, "", "1 of 3 steps at the iteration limit"), 2.0,
                 {0.5, 0.75}, 0.75);
  const json j = summary.to_json();
  EXPECT_EQ(j["cocopp_version"], "0.1.0");
  EXPECT_EQ(j["case"], "examples/tube/case.yaml");
  EXPECT_EQ(j["coupled_solver"], "iqni");
  EXPECT_EQ(j["solvers"], json({"tube_flow", "tube_structure"}));
  EXPECT_DOUBLE_EQ(j["delta_t"].get<double>(), 0.01);
  EXPECT_EQ(j["completed"], true);
  EXPECT_EQ(j["status"], "stalled");
  EXPECT_EQ(j["message"], "");
  EXPECT_EQ(j["reason"], "1 of 3 steps at the iteration limit");
  EXPECT_TRUE(j["stopped_at"].is_null());
  EXPECT_EQ(j["steps_completed"], 3);
  EXPECT_EQ(j["last_step"], 3);
  EXPECT_EQ(j["iterations_per_step"], json({3, 1, 2}));
  EXPECT_DOUBLE_EQ(j["average_iterations"].get<double>(), 2.0);
  EXPECT_EQ(j["unconverged_steps"], json({2}));
  ASSERT_EQ(j["residual_history"].size(), 3u);
  EXPECT_EQ(j["residual_history"][1], json(make_record(2).residual_norms));
  EXPECT_DOUBLE_EQ(j["wall_time"].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(j["solver_times"]["tube_flow"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(j["solver_times"]["tube_structure"].get<double>(), 0.75);
  EXPECT_DOUBLE_EQ(j["coupler_time"].get<double>(), 0.75);
  EXPECT_DOUBLE_EQ(j["coupler_time_per_iteration"].get<double>(), 0.75 / 6);
}

TEST(RunSummary, BeforeFinishItIsRunningWithTimesSummedOverSteps) {
  const json j = summary_of(2).to_json();
  EXPECT_EQ(j["completed"], false);
  EXPECT_EQ(j["status"], "running");
  EXPECT_DOUBLE_EQ(j["wall_time"].get<double>(), 0.1 + 0.2);
  EXPECT_DOUBLE_EQ(j["solver_times"]["tube_structure"].get<double>(), 0.05 + 0.10);
  EXPECT_DOUBLE_EQ(j["coupler_time"].get<double>(),
                   make_record(1).coupler_time + make_record(2).coupler_time);
}

TEST(RunSummary, WithoutStepsAveragesAreNull) {
  RunSummary summary(make_run(5));
  summary.finish(outcome(RunStatus::kSolverFailed, "tube_flow exited with code 1",
                         "solver failure in step 1", 1),
                 0.5, {0.1, 0.2}, 0.2);
  const json j = summary.to_json();
  EXPECT_EQ(j["steps_completed"], 0);
  EXPECT_TRUE(j["last_step"].is_null());
  EXPECT_TRUE(j["average_iterations"].is_null());
  EXPECT_TRUE(j["coupler_time_per_iteration"].is_null());
  EXPECT_EQ(j["iterations_per_step"], json::array());
  EXPECT_EQ(j["status"], "solver_failed");
  EXPECT_EQ(j["completed"], false);
  EXPECT_EQ(j["stopped_at"], json({{"step", 1}, {"iteration", nullptr}}));
}

TEST(RunSummary, ADivergenceSaysWhereItStopped) {
  RunSummary summary = summary_of(2);
  RunOutcome diverged = outcome(RunStatus::kDiverged, "the coupling diverged in time step 3",
                                "residual growth in step 3, iteration 7", 3);
  diverged.divergence = DivergenceKind::kGrowth;
  diverged.iteration = 7;
  summary.finish(diverged, 1.0, {0.25, 0.5}, 0.25);
  const json j = summary.to_json();
  EXPECT_EQ(j["status"], "diverged");
  EXPECT_EQ(j["completed"], false);
  EXPECT_EQ(j["reason"], "residual growth in step 3, iteration 7");
  EXPECT_EQ(j["stopped_at"], json({{"step", 3}, {"iteration", 7}}));
  EXPECT_EQ(diverged.exit_code(), 1);
}

TEST(RunOutcome, StatusNamesAndExitCodes) {
  for (RunStatus status :
       {RunStatus::kCompleted, RunStatus::kStalled, RunStatus::kDiverged, RunStatus::kSolverFailed,
        RunStatus::kInterrupted, RunStatus::kFailed, RunStatus::kInvalidCase})
    EXPECT_EQ(run_status_from_string(to_string(status)), status) << to_string(status);
  EXPECT_THROW(run_status_from_string("finished"), std::invalid_argument);
  EXPECT_EQ(outcome(RunStatus::kCompleted, "", "").exit_code(), 0);
  EXPECT_EQ(outcome(RunStatus::kStalled, "", "").exit_code(), 3);
  EXPECT_EQ(outcome(RunStatus::kInterrupted, "", "").exit_code(), 1);
  EXPECT_EQ(outcome(RunStatus::kInvalidCase, "", "").exit_code(), 2);
  EXPECT_STREQ(to_string(DivergenceKind::kNonFinite), "non-finite values");
}

TEST(RunSummary, RepeatedSolverNamesKeepBothTimes) {
  RunDescription run = make_run(1);
  run.solver_names = {"tube", "tube"};
  RunSummary summary(run);
  summary.finish(RunOutcome{}, 1.0, {0.25, 0.5}, 0.25);
  const json times = summary.to_json()["solver_times"];
  EXPECT_EQ(times, json({{"tube", 0.25}, {"tube_2", 0.5}}));
}

TEST(RunSummary, RejectsSolverTimesOfTheWrongLength) {
  RunSummary summary(make_run(1));
  StepRecord record = make_record(1);
  record.solver_times = {1.0};
  EXPECT_THROW(summary.add_step(record), std::invalid_argument);
  EXPECT_THROW(summary.finish(RunOutcome{}, 1, {1, 2, 3}, 0), std::invalid_argument);
}

TEST(RunSummary, NonFiniteResidualsAndBadUtf8StillWrite) {
  const auto dir = test_directory();
  RunSummary summary(make_run(1));
  StepRecord record = make_record(1);
  record.residual_norms = {1.0, std::numeric_limits<double>::quiet_NaN()};
  summary.add_step(record);
  summary.finish(outcome(RunStatus::kDiverged, "residual is \xff", "", 1), 1, {0, 0}, 1);
  summary.write(dir / "summary.json");
  const json j = read_json(dir / "summary.json");
  EXPECT_TRUE(j["residual_history"][0][1].is_null());
  EXPECT_EQ(j["message"], "residual is \xef\xbf\xbd");
}

TEST(RunSummary, WriteCreatesTheDirectoryAndReplacesTheFile) {
  const auto dir = test_directory() / "nested";
  const auto file = dir / "run.summary.json";
  summary_of(1).write(file);
  EXPECT_EQ(read_json(file)["steps_completed"], 1);
  const RunSummary second = summary_of(3);
  second.write(file);
  EXPECT_EQ(read_json(file), second.to_json());
  EXPECT_EQ(directory_entries(dir), std::vector<std::string>{"run.summary.json"})
      << "no temporary file may be left behind";
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\n  \"case\""), std::string::npos) << "written indented:\n" << text;
}

TEST(RunSummary, AFailedWriteKeepsTheOldFileAndLeavesNoTemporary) {
  const auto dir = test_directory();
  const auto file = dir / "run.summary.json";
  summary_of(1).write(file);
  // Occupy the temporary name with a directory so that writing the new contents fails.
  const auto blocker = dir / ("run.summary.json.tmp." + std::to_string(::getpid()));
  std::filesystem::create_directories(blocker / "x");
  EXPECT_THROW(summary_of(3).write(file), std::runtime_error);
  EXPECT_EQ(read_json(file)["steps_completed"], 1);
  std::filesystem::remove_all(blocker);

  // A rename onto a directory fails after the temporary is written: it must be removed.
  const auto occupied = dir / "occupied";
  std::filesystem::create_directories(occupied / "x");
  try {
    summary_of(1).write(occupied);
    ADD_FAILURE() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("occupied"), std::string::npos) << e.what();
  }
  EXPECT_EQ(directory_entries(dir), (std::vector<std::string>{"occupied", "run.summary.json"}));
}

}  // namespace
}  // namespace cocopp::test
