// ProcessSolverWrapper driving cocopp-test-solver (tests/support) end to end, over both
// transports, and through each way a solver can fail.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <thread>

#include "core/protocol/pipe_transport.hpp"
#include "solver_wrappers/process/process_solver_wrapper.hpp"
#include "solver_wrappers/process/python_hint.hpp"
#include "solver_wrappers/solver_error.hpp"
#include "tests/support/error_message.hpp"
#include "tests/support/temporary_directory.hpp"

namespace cocopp {
namespace {

using testing::error_message;
using testing::process_alive;
using testing::read_text;
using testing::TemporaryDirectory;
using testing::write_text;
using Clock = std::chrono::steady_clock;

std::filesystem::path bin_directory() {
  const char* directory = std::getenv("COCOPP_BIN_DIR");
  return directory != nullptr ? directory : COCOPP_TEST_BIN_DIR;
}

std::unique_ptr<SolverWrapper> create(const std::string& yaml, const RunSettings& run) {
  const Settings settings = Settings::load_string(yaml, "case.yaml");
  auto wrapper = SolverWrapperRegistry::instance().create(settings, run);
  settings.check_unused_keys();
  return wrapper;
}

/// The message of the SolverError `action` throws (fails the test if it throws none).
template <class Action>
std::string solver_error_of(Action&& action) {
  try {
    action();
  } catch (const SolverError& e) {
    EXPECT_EQ(e.solver_name(), "flow");
    return e.what();
  }
  ADD_FAILURE() << "no SolverError";
  return "";
}

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << "in: " << (text)

class ProcessSolverWrapperTest : public ::testing::TestWithParam<std::string> {
 protected:
  ProcessSolverWrapperTest() {
    run_.delta_t = 0.01;
    run_.timestep_start = 0;
    run_.case_directory = directory_.path();
    std::filesystem::create_directory(directory_ / "flow");
  }

  /// The test solver in working directory `flow`, with `input` as its input file.
  ProcessSolverWrapper& start(const std::string& input, const std::string& extra_keys = "") {
    write_text(directory_ / "flow/test_solver.in", input);
    wrapper_ = create(
        "type: process\n"
        "name: flow\n"
        "working_directory: flow\n"
        "command: [" +
            (bin_directory() / "cocopp-test-solver").string() +
            ", test_solver.in]\n"
            "transport: " +
            GetParam() + "\n" + extra_keys,
        run_);
    auto& wrapper = dynamic_cast<ProcessSolverWrapper&>(*wrapper_);
    return wrapper;
  }

  static void set_y_displacement(Interface& input, double value) {
    auto displacement = input.values("wall", "displacement");
    for (Eigen::Index i = 0; i < displacement.rows(); ++i) {
      displacement(i, 0) = 0.5 * value;
      displacement(i, 1) = value * (i + 1);
      displacement(i, 2) = -value;
    }
  }

  /// After any end of a solver: no process left, no channel files left.
  void expect_cleaned_up(const ProcessSolverWrapper& wrapper) const {
    EXPECT_GT(wrapper.child_pid(), 0);
    EXPECT_FALSE(process_alive(wrapper.child_pid()));
    for (const auto& entry : std::filesystem::directory_iterator(directory_ / "flow")) {
      const std::string name = entry.path().filename().string();
      EXPECT_TRUE(name == "test_solver.in" || name == "flow.log") << "left behind: " << name;
    }
  }

  TemporaryDirectory directory_;
  RunSettings run_;
  std::unique_ptr<SolverWrapper> wrapper_;
};

TEST_P(ProcessSolverWrapperTest, RunsStepsAndStops) {
  run_.timestep_start = 5;
  auto& wrapper = start("points 5\n");
  wrapper.initialize();
  EXPECT_GT(wrapper.solver_pid(), 0);
  EXPECT_EQ(wrapper.input_interface().describe(), "wall: displacement (5 x 3)");
  EXPECT_EQ(wrapper.output_interface().describe(),
            "wall: pressure (5 x 1); wall: traction (5 x 3)");
  // One model part object behind both interfaces.
  EXPECT_EQ(wrapper.input_interface().parts()[0].model_part,
            wrapper.output_interface().parts()[0].model_part);
  const auto& wall = *wrapper.input_interface().parts()[0].model_part;
  EXPECT_EQ(wall.ids, (std::vector<std::int64_t>{1, 2, 3, 4, 5}));
  EXPECT_DOUBLE_EQ(wall.coordinates(3, 0), 0.3);
  EXPECT_DOUBLE_EQ(wall.coordinates(3, 1), 0.005);
  // Initial output: pressure 100 + i + timestep_start, traction (delta_t, 0, 0).
  EXPECT_EQ(wrapper.output_interface().values("wall", "pressure")(2, 0), 107.0);
  EXPECT_EQ(wrapper.output_interface().values("wall", "traction")(4, 0), 0.01);

  Interface input = wrapper.input_interface();
  for (int step = 6; step <= 8; ++step) {
    wrapper.initialize_step(step, step * run_.delta_t);
    for (int iteration = 1; iteration <= 2; ++iteration) {
      const double amplitude = 1e-4 * iteration;
      set_y_displacement(input, amplitude);
      const Interface& output = wrapper.solve(input);
      const auto pressure = output.values("wall", "pressure");
      const auto traction = output.values("wall", "traction");
      for (Eigen::Index i = 0; i < 5; ++i) {
        EXPECT_DOUBLE_EQ(pressure(i, 0), 1000.0 * amplitude * (i + 1) + step);
        EXPECT_DOUBLE_EQ(traction(i, 1), 2.0 * amplitude * (i + 1));
        EXPECT_DOUBLE_EQ(traction(i, 2), -2.0 * amplitude);
      }
    }
    wrapper.finalize_step();
    wrapper.output_step();
  }
  wrapper.finalize();
  wrapper.finalize();  // twice is fine
  expect_cleaned_up(wrapper);
  const std::string log = read_text(directory_ / "flow/flow.log");
  EXPECT_CONTAINS(log, "test solver: initialize, delta_t 0.01, timestep_start 5, 5 points");
  EXPECT_CONTAINS(log, "test solver: step 8 iteration 2");
  EXPECT_CONTAINS(log, "test solver: finalize");
}

// As the coupler runs a solver: its step requests overlapped (their replies read with the
// next request) and, with `solver_busy_wait`, the solver reading its requests without
// sleeping (pipe transport): the same answers, a clean stop.
TEST_P(ProcessSolverWrapperTest, OverlappedStepRequestsAndTheSolversBusyWaitGiveTheSameAnswers) {
  auto& wrapper = start("points 3\n", "solver_busy_wait: 0.002\n");
  wrapper.initialize();
  wrapper.overlap_step_requests();
  Interface input = wrapper.input_interface();
  for (int step = 1; step <= 4; ++step) {
    wrapper.initialize_step(step, step * run_.delta_t);
    for (int iteration = 1; iteration <= 3; ++iteration) {
      const double amplitude = 1e-4 * iteration;
      set_y_displacement(input, amplitude);
      const auto pressure = wrapper.solve(input).values("wall", "pressure");
      for (Eigen::Index i = 0; i < 3; ++i)
        EXPECT_DOUBLE_EQ(pressure(i, 0), 1000.0 * amplitude * (i + 1) + step);
    }
    wrapper.finalize_step();
    wrapper.output_step();
    wrapper.complete_step_requests();
  }
  wrapper.finalize_step();  // a request still in flight when the solver is stopped
  wrapper.finalize();
  expect_cleaned_up(wrapper);
  const std::string log = read_text(directory_ / "flow/flow.log");
  EXPECT_CONTAINS(log, "test solver: COCOPP_BUSY_WAIT=0.002");
  EXPECT_CONTAINS(log, "test solver: step 4 iteration 3");
  EXPECT_CONTAINS(log, "test solver: finalize");
}

TEST_P(ProcessSolverWrapperTest, NaNValuesArriveAsNaN) {
  auto& wrapper = start("points 3\nfail nan\nfail_step 1\nfail_iteration 2\n");
  wrapper.initialize();
  Interface input = wrapper.input_interface();
  wrapper.initialize_step(1, 0.01);
  EXPECT_TRUE(wrapper.solve(input).data().allFinite());
  const Interface& output = wrapper.solve(input);
  EXPECT_TRUE(std::isnan(output.data()(0)));
  EXPECT_TRUE(output.data().array().isNaN().all());
  wrapper.finalize();
  expect_cleaned_up(wrapper);
}

TEST_P(ProcessSolverWrapperTest, ACrashIsReportedWithItsSignalAndTheLogTail) {
  auto& wrapper = start("fail crash\nfail_step 2\nfail_iteration 1\n");
  wrapper.initialize();
  Interface input = wrapper.input_interface();
  wrapper.initialize_step(1, 0.01);
  wrapper.solve(input);
  wrapper.finalize_step();
  wrapper.initialize_step(2, 0.02);
  const std::string message = solver_error_of([&] { wrapper.solve(input); });
  EXPECT_CONTAINS(message, "solver 'flow' (pid " + std::to_string(wrapper.child_pid()) + ")");
  EXPECT_CONTAINS(message, "killed by signal 11 (Segmentation fault)");
  EXPECT_CONTAINS(message, "during solve at step 2, iteration 1");
  EXPECT_CONTAINS(message, (directory_ / "flow/flow.log").string());
  EXPECT_CONTAINS(message, "test solver: failing (crash) at step 2 iteration 1");
  expect_cleaned_up(wrapper);
  EXPECT_NO_THROW(wrapper.finalize());
  EXPECT_CONTAINS(solver_error_of([&] { wrapper.solve(input); }), "is not running");
}

TEST_P(ProcessSolverWrapperTest, AnExitCodeIsReported) {
  auto& wrapper = start("fail exit\nfail_step 1\n");
  wrapper.initialize();
  wrapper.initialize_step(1, 0.01);
  const std::string message = solver_error_of([&] { wrapper.solve(wrapper.input_interface()); });
  EXPECT_CONTAINS(message, "exited with code 3 during solve at step 1, iteration 1");
  expect_cleaned_up(wrapper);
}

TEST_P(ProcessSolverWrapperTest, AHangingSolverTimesOut) {
  auto& wrapper = start("fail hang\nfail_step 1\n", "timeout: 0.5\n");
  wrapper.initialize();
  wrapper.initialize_step(1, 0.01);
  const auto begin = Clock::now();
  const std::string message = solver_error_of([&] { wrapper.solve(wrapper.input_interface()); });
  EXPECT_LT(std::chrono::duration<double>(Clock::now() - begin).count(), 5.0);
  EXPECT_CONTAINS(message, "solver 'flow' did not answer solve within 0.5 s (step 1, iteration 1)");
  EXPECT_CONTAINS(message, "ends with:\n");
  EXPECT_CONTAINS(message, "test solver: failing (hang) at step 1 iteration 1");
  expect_cleaned_up(wrapper);
}

TEST_P(ProcessSolverWrapperTest, AReportedErrorIsRelayed) {
  auto& wrapper = start("fail error\nfail_step 1\nfail_iteration 2\n");
  wrapper.initialize();
  wrapper.initialize_step(1, 0.01);
  wrapper.solve(wrapper.input_interface());
  const std::string message = solver_error_of([&] { wrapper.solve(wrapper.input_interface()); });
  EXPECT_EQ(message.rfind("solver 'flow' reported an error: test solver: requested error at step "
                          "1 iteration 2",
                          0),
            0u)
      << message;
  expect_cleaned_up(wrapper);
}

// Issue 17, defects 4 and 10: a solver's error text reaches the user cut to a few kilobytes
// and without control characters; one longer than any text the coupler accepts is refused
// unread as a corrupt stream. Both end cleanly.
TEST_P(ProcessSolverWrapperTest, LongErrorTextsAreCutAndStrippedOfControlCharacters) {
  auto& wrapper = start("fail error\nfail_step 1\nerror_bytes 60000\n");
  wrapper.initialize();
  wrapper.initialize_step(1, 0.01);
  const std::string message = solver_error_of([&] { wrapper.solve(wrapper.input_interface()); });
  EXPECT_CONTAINS(message, "test solver: ?[2J requested long error at step 1 iteration 1");
  EXPECT_CONTAINS(message, "more bytes]");
  EXPECT_EQ(message.find('\x1b'), std::string::npos);
  // The text (4 KiB), and the log tail (16 KiB) where the solver's stderr repeats it.
  EXPECT_LT(message.size(), 24u * 1024);
  expect_cleaned_up(wrapper);

  auto& huge = start("fail error\nfail_step 1\nerror_bytes 1000000\n");
  huge.initialize();
  huge.initialize_step(1, 0.01);
  const std::string refused = solver_error_of([&] { huge.solve(huge.input_interface()); });
  EXPECT_CONTAINS(refused, "the largest this channel takes now is");
  expect_cleaned_up(huge);
}

// A rejected input is no failure: the solver serves on and solves the next input.
TEST_P(ProcessSolverWrapperTest, ARejectedInputIsRelayedAndTheSolverServesOn) {
  auto& wrapper = start("points 2\nfail reject\nfail_step 1\nfail_iteration 2\n");
  wrapper.initialize();
  wrapper.initialize_step(1, 0.01);
  Interface input = wrapper.input_interface();
  input.values("wall", "displacement").setConstant(0.5);
  const Eigen::VectorXd first = wrapper.solve(input).data();
  const std::string message = cocopp::testing::error_message<SolverRejectedInput>(
      [&] { wrapper.solve(wrapper.input_interface()); });
  EXPECT_EQ(message.rfind("solver 'flow' rejected the input at step 1, iteration 2: test solver: "
                          "requested rejection at step 1 iteration 2",
                          0),
            0u)
      << message;
  EXPECT_CONTAINS(message, (directory_ / "flow/flow.log").string());
  EXPECT_EQ(wrapper.solve(input).data(), first);
  wrapper.finalize_step();
  wrapper.finalize();
  expect_cleaned_up(wrapper);
}

TEST_P(ProcessSolverWrapperTest, AnErrorDuringInitializeIsRelayed) {
  auto& wrapper = start("points 2\nfail_mode error\n");
  const std::string message = solver_error_of([&] { wrapper.initialize(); });
  EXPECT_CONTAINS(message, "reported an error: test solver: ");
  EXPECT_CONTAINS(message, "unknown key 'fail_mode'");
  EXPECT_CONTAINS(message, "during initialize before the first step");
  expect_cleaned_up(wrapper);
}

TEST_P(ProcessSolverWrapperTest, ACrashDuringInitializeIsReported) {
  auto& wrapper = start("fail crash\nfail_step 0\n");
  const std::string message = solver_error_of([&] { wrapper.initialize(); });
  EXPECT_CONTAINS(message, "killed by signal 11 (Segmentation fault) during initialize");
  expect_cleaned_up(wrapper);
}

TEST_P(ProcessSolverWrapperTest, TheDestructorStopsARunningSolver) {
  auto& wrapper = start("points 2\n", "log_file: logs/flow.log\n");
  wrapper.initialize();
  wrapper.initialize_step(1, 0.01);
  const int pid = wrapper.child_pid();
  EXPECT_TRUE(process_alive(pid));
  wrapper_.reset();
  EXPECT_FALSE(process_alive(pid));
  EXPECT_CONTAINS(read_text(directory_ / "flow/logs/flow.log"), "test solver: finalize");
  EXPECT_FALSE(std::filesystem::exists(directory_ / "flow/to_solver_00000001.msg"));
  EXPECT_FALSE(
      std::filesystem::exists(directory_ / "flow" / protocol::PipeTransport::kToSolverFifo));
}

INSTANTIATE_TEST_SUITE_P(Transports, ProcessSolverWrapperTest,
                         ::testing::Values("pipe", "file", "tcp"),
                         [](const auto& info) { return info.param; });

class ProcessSolverWrapperSetupTest : public ::testing::Test {
 protected:
  ProcessSolverWrapperSetupTest() {
    run_.case_directory = directory_.path();
    std::filesystem::create_directory(directory_ / "flow");
  }

  std::unique_ptr<SolverWrapper> create_flow(const std::string& keys) {
    return create("type: process\nname: flow\nworking_directory: flow\n" + keys, run_);
  }

  TemporaryDirectory directory_;
  RunSettings run_;
};

TEST_F(ProcessSolverWrapperSetupTest, AMissingExecutableIsNamedByCheckAndInitialize) {
  auto wrapper = create_flow("command: [./no_such_solver, input.txt]\n");
  std::string message = error_message<CaseError>([&] { wrapper->check(); });
  EXPECT_CONTAINS(message, "case.yaml:4:");
  EXPECT_CONTAINS(message, "solver 'flow': executable " +
                               (directory_ / "flow/no_such_solver").string() + " does not exist");
  message = error_message<CaseError>([&] { wrapper->initialize(); });
  EXPECT_CONTAINS(message, "no_such_solver");
  EXPECT_NO_THROW(wrapper->finalize());

  wrapper = create_flow("command: [no_such_solver_on_path]\n");
  EXPECT_CONTAINS(error_message<CaseError>([&] { wrapper->check(); }),
                  "executable 'no_such_solver_on_path' not found in " +
                      (directory_ / "flow").string() + " or on PATH");
}

TEST_F(ProcessSolverWrapperSetupTest, AMissingWorkingDirectoryIsReported) {
  auto wrapper =
      create("type: process\nname: flow\nworking_directory: nowhere\ncommand: [sh]\n", run_);
  EXPECT_CONTAINS(error_message<CaseError>([&] { wrapper->check(); }),
                  "working directory " + (directory_ / "nowhere").string() + " does not exist");
}

TEST_F(ProcessSolverWrapperSetupTest, ASolverThatNeverConnectsTimesOut) {
  auto wrapper = create_flow("command: [/bin/sleep, '30']\nstartup_timeout: 0.3\n");
  auto& process = dynamic_cast<ProcessSolverWrapper&>(*wrapper);
  const std::string message = solver_error_of([&] { wrapper->initialize(); });
  EXPECT_CONTAINS(message, "solver 'flow' did not connect within 0.3 s (before the first step)");
  EXPECT_FALSE(process_alive(process.child_pid()));
  EXPECT_FALSE(
      std::filesystem::exists(directory_ / "flow" / protocol::PipeTransport::kToSolverFifo));
}

/// The test solver started as a user would, from outside the coupler: once `channel_file`
/// appears (within 10 s), with COCOPP_CHANNEL_FILE naming it, in `directory`. Its pid (0 if
/// the file never came); `mode` gets the file's permission bits.
pid_t start_by_hand(const std::filesystem::path& channel_file,
                    const std::filesystem::path& directory, std::filesystem::perms& mode) {
  const auto end = Clock::now() + std::chrono::seconds(10);
  while (!std::filesystem::exists(channel_file) && Clock::now() < end)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  if (!std::filesystem::exists(channel_file)) return 0;
  mode = std::filesystem::status(channel_file).permissions();
  const std::string solver = (bin_directory() / "cocopp-test-solver").string();
  // Everything the child needs is made before fork(): after it, in a process with threads,
  // only async-signal-safe calls (chdir, execve).
  std::vector<std::string> variables = {"COCOPP_CHANNEL_FILE=" + channel_file.string()};
  for (char** entry = environ; *entry != nullptr; ++entry)
    if (std::string(*entry).rfind("COCOPP_", 0) != 0 ||
        std::string(*entry).rfind("COCOPP_BIN", 0) == 0)
      variables.emplace_back(*entry);
  std::vector<char*> envp;
  for (auto& variable : variables) envp.push_back(variable.data());
  envp.push_back(nullptr);
  std::string input = "test_solver.in";
  char* argv[] = {const_cast<char*>(solver.c_str()), input.data(), nullptr};
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(directory.c_str()) != 0) ::_exit(127);
    ::execve(solver.c_str(), argv, envp.data());
    ::_exit(127);
  }
  return pid;
}

// Issue 50: a solver the user starts (a batch script's srun, another terminal) with
// started_by: user. The coupler writes the channel's address and token to a file only the
// user can read, waits for the solver there, removes the file once it is in, and runs it as
// any other; its death mid-run is a closed connection, named. Nobody starting it is a timeout
// that says how to start it.
TEST_F(ProcessSolverWrapperSetupTest, ASolverTheUserStartsConnectsThroughTheChannelFile) {
  write_text(directory_ / "flow/test_solver.in", "points 3\n");
  const auto channel_file = directory_ / "flow/cocopp_channel_flow.env";
  auto wrapper = create_flow("started_by: user\ntransport: tcp\nstartup_timeout: 20\n");
  auto& process = dynamic_cast<ProcessSolverWrapper&>(*wrapper);
  EXPECT_NO_THROW(wrapper->check());
  EXPECT_CONTAINS(process.describe(), "flow: started by the user (in ");
  std::filesystem::perms mode{};
  pid_t solver = 0;
  std::thread user([&] { solver = start_by_hand(channel_file, directory_ / "flow", mode); });
  wrapper->initialize();
  user.join();
  ASSERT_GT(solver, 0);
  EXPECT_EQ(mode, std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
  EXPECT_FALSE(std::filesystem::exists(channel_file));  // used: gone
  EXPECT_EQ(process.solver_pid(), solver);
  Interface input = wrapper->input_interface();
  wrapper->initialize_step(1, 0.01);
  EXPECT_EQ(wrapper->solve(input).values("wall", "pressure")(0, 0), 1.0);
  wrapper->finalize_step();
  ::kill(solver, SIGKILL);
  ::waitpid(solver, nullptr, 0);
  const std::string lost = solver_error_of([&] {
    wrapper->initialize_step(2, 0.02);
    wrapper->solve(input);
  });
  EXPECT_CONTAINS(lost, "solver 'flow' (started by the user) closed the connection during ");
  EXPECT_CONTAINS(lost, "step 2");

  auto unstarted = create_flow("started_by: user\ntransport: tcp\nstartup_timeout: 0.3\n");
  EXPECT_CONTAINS(solver_error_of([&] { unstarted->initialize(); }),
                  "solver 'flow' (started by the user) did not connect within 0.3 s (before the "
                  "first step): start it with COCOPP_CHANNEL_FILE=" +
                      channel_file.string());
  EXPECT_FALSE(std::filesystem::exists(channel_file));

  EXPECT_CONTAINS(error_message<CaseError>([&] { create_flow("started_by: user\n"); }),
                  "'started_by': a solver the user starts connects over TCP: add transport: tcp");
  EXPECT_CONTAINS(error_message<CaseError>(
                      [&] { create_flow("started_by: user\ntransport: tcp\ncommand: [./s]\n"); }),
                  "'command': the coupler starts nothing for a solver with started_by: user");
}

TEST_F(ProcessSolverWrapperSetupTest, AProgramThatIsNoSolverIsReported) {
  auto wrapper = create_flow("command: [/bin/sh, -c, 'echo I am no solver; exit 7']\n");
  const std::string message = solver_error_of([&] { wrapper->initialize(); });
  EXPECT_CONTAINS(message, "exited with code 7 during startup before the first step");
  EXPECT_CONTAINS(message, "I am no solver");
}

// Issue 51: a Python solver that dies for want of a module names the interpreter its command
// ran (a python3 first on PATH may lack NumPy) and what to change; for cocopp_sdk, where it is.
TEST_F(ProcessSolverWrapperSetupTest, APythonSolverWithoutItsModuleIsToldWhichInterpreterRan) {
  auto wrapper =
      create_flow("command: [/usr/bin/python3, -c, 'import no_such_module_of_cocopp']\n");
  const std::string message = solver_error_of([&] { wrapper->initialize(); });
  EXPECT_CONTAINS(message, "No module named 'no_such_module_of_cocopp'");
  EXPECT_CONTAINS(message, "hint: the solver's command ran /usr/bin/python3");
  EXPECT_CONTAINS(message, "which has no module 'no_such_module_of_cocopp'");
  EXPECT_CONTAINS(message, "command: [/usr/bin/python3, ...]");

  const std::string tail = "ModuleNotFoundError: No module named 'cocopp_sdk'\n";
  EXPECT_CONTAINS(python_module_hint({"python3", "wall.py"}, "/usr/local/bin/python3", tail, ""),
                  "ran python3 (found as /usr/local/bin/python3)");
  EXPECT_CONTAINS(python_module_hint({"python3", "wall.py"}, "/usr/bin/python3", tail,
                                     "/opt/cocopp/lib/python3/dist-packages"),
                  "export PYTHONPATH=/opt/cocopp/lib/python3/dist-packages");
  EXPECT_EQ(python_module_hint({"python3"}, "/usr/bin/python3", "Traceback: KeyError", ""), "");
}

TEST_F(ProcessSolverWrapperSetupTest, DefaultsAndPaths) {
  auto wrapper = create_flow("command: [./solver]\n");
  auto& process = dynamic_cast<ProcessSolverWrapper&>(*wrapper);
  EXPECT_EQ(process.name(), "flow");
  EXPECT_EQ(process.working_directory(), directory_ / "flow");
  EXPECT_EQ(process.log_file(), directory_ / "flow/flow.log");
  EXPECT_EQ(process.transport(), protocol::TransportKind::kPipe);
  EXPECT_EQ(process.describe(), "flow: ./solver (in " + (directory_ / "flow").string() + "; log " +
                                    (directory_ / "flow/flow.log").string() + "; pipe transport)");
  auto unnamed = create(
      "type: process\nworking_directory: flow\ncommand: [./solver]\n"
      "log_file: logs/out.txt\n",
      run_);
  EXPECT_EQ(unnamed->name(), "process");
  EXPECT_EQ(dynamic_cast<ProcessSolverWrapper&>(*unnamed).log_file(),
            directory_ / "flow/logs/out.txt");
}

TEST_F(ProcessSolverWrapperSetupTest, SettingsAreValidatedWhenBuilt) {
  EXPECT_CONTAINS(
      error_message<CaseError>([&] { create_flow("command: [./s]\ntransport: pipes\n"); }),
      "did you mean 'pipe'");
  EXPECT_CONTAINS(error_message<CaseError>([&] { create_flow("command: [./s]\ntimeout: 0\n"); }),
                  "'timeout': must be in (0, 10000000], got 0");
  EXPECT_CONTAINS(error_message<CaseError>([&] { create_flow(""); }),
                  "missing required key 'command'");
  EXPECT_CONTAINS(error_message<CaseError>([&] { create_flow("command: []\n"); }),
                  "must start with the executable");
  EXPECT_CONTAINS(error_message<CaseError>([&] { create_flow("command: [./s]\ntimout: 5\n"); }),
                  "unknown key 'timout'; did you mean 'timeout'");
  EXPECT_CONTAINS(error_message<CaseError>([&] { create_flow("command: [./s]\ninput_file: x\n"); }),
                  "unknown key 'input_file'");
  // transport: tcp's keys (docs/clusters.md).
  EXPECT_CONTAINS(error_message<CaseError>([&] { create_flow("command: [./s]\nport: 4000\n"); }),
                  "'port': is a key of transport: tcp (this solver uses pipe)");
  EXPECT_CONTAINS(error_message<CaseError>(
                      [&] { create_flow("command: [./s]\ntransport: tcp\nport: 70000\n"); }),
                  "'port'");
  EXPECT_CONTAINS(error_message<CaseError>(
                      [&] { create_flow("command: [./s]\ntransport: tcp\nhost: 'a b'\n"); }),
                  "give an address or a name of this machine");
  EXPECT_CONTAINS(error_message<CaseError>([&] { create_flow("command: [./s]\nlauncher: []\n"); }),
                  "give the command that starts the solver elsewhere");
  const auto launched = create_flow("command: [./s]\nlauncher: [srun, -N1]\ntransport: tcp\n");
  EXPECT_CONTAINS(dynamic_cast<ProcessSolverWrapper&>(*launched).describe(), "srun -N1 ./s (in ");
}

TEST_F(ProcessSolverWrapperSetupTest, BuiltinTubeSolversDefaultToTheBinDirectory) {
  // Point COCOPP_BIN_DIR at a fake bin directory, so that this test does not depend on the
  // tube executables; its cocopp-tube-flow checks its input as the real one's --check does
  // (tested in test_tube_executables): an empty file is refused.
  TemporaryDirectory bin;
  write_text(bin / "cocopp-tube-flow",
             "#!/bin/sh\n[ \"$1\" = --check ] || exit 3\n[ -s \"$2\" ] && exit 0\n"
             "echo \"$2: the file must hold a mapping of keys\" >&2\nexit 1\n");
  std::filesystem::permissions(bin / "cocopp-tube-flow", std::filesystem::perms::owner_all);
  const char* saved = std::getenv("COCOPP_BIN_DIR");
  const std::string saved_value = saved != nullptr ? saved : "";
  ::setenv("COCOPP_BIN_DIR", bin.path().c_str(), 1);

  const auto command_of = [&](const std::string& yaml) {
    return dynamic_cast<ProcessSolverWrapper&>(*create(yaml, run_)).command();
  };
  EXPECT_EQ(command_of("type: tube_flow\nworking_directory: flow\n"),
            (std::vector<std::string>{(bin / "cocopp-tube-flow").string(), "tube_flow.yaml"}));
  EXPECT_EQ(command_of("type: tube_structure\nworking_directory: flow\ninput_file: s.yaml\n"),
            (std::vector<std::string>{(bin / "cocopp-tube-structure").string(), "s.yaml"}));
  EXPECT_EQ(command_of("type: tube_ringmodel\nworking_directory: flow\n")[1],
            "tube_ringmodel.yaml");
  EXPECT_EQ(command_of("type: tube_flow\nworking_directory: flow\ncommand: [./mine]\n"),
            (std::vector<std::string>{"./mine"}));
  EXPECT_CONTAINS(
      error_message<CaseError>([&] {
        create("type: tube_flow\nworking_directory: flow\ncommand: [a]\ninput_file: b\n", run_);
      }),
      "give either 'command' or 'input_file'");

  auto flow = create("type: tube_flow\nworking_directory: flow\n", run_);
  EXPECT_EQ(flow->name(), "tube_flow");
  EXPECT_CONTAINS(
      error_message<CaseError>([&] { flow->check(); }),
      "input file " + (directory_ / "flow/tube_flow.yaml").string() + " does not exist");
  write_text(directory_ / "flow/tube_flow.yaml", "");
  EXPECT_NO_THROW(flow->check());
  // check_solver_input() has cocopp-tube-flow read its input file, in its working directory.
  const std::string refused = error_message<CaseError>([&] { flow->check_solver_input(); });
  EXPECT_CONTAINS(refused, "solver 'tube_flow' refuses its input file");
  EXPECT_CONTAINS(refused, "tube_flow.yaml: the file must hold a mapping of keys");
  const std::string input = read_text(std::filesystem::path(COCOPP_TEST_SOURCE_DIR) /
                                      "examples/tube/flow_structure/flow/tube_flow.yaml");
  write_text(directory_ / "flow/tube_flow.yaml", input);
  EXPECT_NO_THROW(flow->check_solver_input());
  auto structure = create("type: tube_structure\nworking_directory: flow\n", run_);
  EXPECT_CONTAINS(error_message<CaseError>([&] { structure->check(); }), "cocopp-tube-structure");

  if (saved != nullptr)
    ::setenv("COCOPP_BIN_DIR", saved_value.c_str(), 1);
  else
    ::unsetenv("COCOPP_BIN_DIR");
}

// The protocol from another language: tests/support/python_solver.py, the example of
// docs/protocol.md, written without the SDK.
TEST_F(ProcessSolverWrapperSetupTest, ASolverWrittenInPythonWorks) {
  const std::filesystem::path script =
      std::filesystem::path(COCOPP_TEST_SOURCE_DIR) / "tests/support/python_solver.py";
  auto wrapper = create_flow("command: [/usr/bin/python3, " + script.string() + "]\n");
  wrapper->initialize();
  EXPECT_EQ(wrapper->input_interface().describe(), "wall: displacement (3 x 3)");
  EXPECT_EQ(wrapper->output_interface().describe(), "wall: pressure (3 x 1)");
  Interface input = wrapper->input_interface();
  input.values("wall", "displacement")(2, 1) = 0.002;
  for (int step = 1; step <= 2; ++step) {
    wrapper->initialize_step(step, 0.1 * step);
    const auto pressure = wrapper->solve(input).values("wall", "pressure");
    EXPECT_DOUBLE_EQ(pressure(0, 0), step);
    EXPECT_DOUBLE_EQ(pressure(2, 0), 2.0 + step);
    wrapper->finalize_step();
    wrapper->output_step();
  }
  wrapper->finalize();
  auto& process = dynamic_cast<ProcessSolverWrapper&>(*wrapper);
  EXPECT_FALSE(process_alive(process.child_pid()));
}

TEST(SolverExecutableTest, WithoutTheCouplerItSaysHowToRunIt) {
  TemporaryDirectory directory;
  const std::string solver = (bin_directory() / "cocopp-test-solver").string();
  const std::string log = (directory / "out.txt").string();
  const std::string environment = "env -u COCOPP_TRANSPORT -u COCOPP_CHANNEL ";
  int status = std::system((environment + solver + " > " + log + " 2>&1").c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_CONTAINS(read_text(log),
                  "this program is a cocopp solver; run it through `cocopp run case.yaml`");
  status = std::system((environment + solver + " --help > " + log + " 2>&1").c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_CONTAINS(read_text(log), "is a cocopp solver");
}

}  // namespace
}  // namespace cocopp
