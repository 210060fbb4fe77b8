#include <gtest/gtest.h>
#include <sys/stat.h>

#include <csignal>
#include <thread>

#include "solver_wrappers/process/child_process.hpp"
#include "tests/support/temporary_directory.hpp"

namespace cocopp {
namespace {

using testing::process_alive;
using testing::read_text;
using testing::TemporaryDirectory;
using testing::write_text;

class ChildProcessTest : public ::testing::Test {
 protected:
  ChildOptions shell(const std::string& script) const {
    ChildOptions options;
    options.command = {"/bin/sh", "-c", script};
    options.working_directory = directory_.path();
    options.log_file = directory_ / "child.log";
    return options;
  }

  TemporaryDirectory directory_;
};

TEST_F(ChildProcessTest, ReportsTheExitCodeAndLogsStdoutAndStderr) {
  ChildProcess child(shell("echo to stdout; echo to stderr >&2; exit 3"));
  ASSERT_TRUE(child.wait_for_exit(10.0));
  EXPECT_EQ(child.describe_exit(), "exited with code 3");
  EXPECT_EQ(child.exit_code(), 3);
  EXPECT_EQ(read_text(directory_ / "child.log"), "to stdout\nto stderr\n");
}

TEST_F(ChildProcessTest, ReportsTheSignalThatKilledIt) {
  ChildProcess child(shell("kill -SEGV $$"));
  ASSERT_TRUE(child.wait_for_exit(10.0));
  EXPECT_EQ(child.describe_exit().rfind("killed by signal 11 (Segmentation fault)", 0), 0u)
      << child.describe_exit();
  EXPECT_EQ(child.exit_code(), -1);
}

TEST_F(ChildProcessTest, RunsInItsWorkingDirectoryWithTheExtraEnvironment) {
  auto options = shell("pwd; echo \"$COCOPP_TEST_VALUE\"");
  options.environment = {{"COCOPP_TEST_VALUE", "forty two"}};
  ChildProcess child(options);
  ASSERT_TRUE(child.wait_for_exit(10.0));
  const std::string expected =
      std::filesystem::canonical(directory_.path()).string() + "\nforty two\n";
  EXPECT_EQ(read_text(directory_ / "child.log"), expected);
}

TEST_F(ChildProcessTest, LogIsTruncatedOrAppendedOnRequest) {
  write_text(directory_ / "child.log", "old\n");
  auto options = shell("echo new");
  options.truncate_log = false;
  ChildProcess(options).wait_for_exit(10.0);
  EXPECT_EQ(read_text(directory_ / "child.log"), "old\nnew\n");
  options.truncate_log = true;
  ChildProcess(options).wait_for_exit(10.0);
  EXPECT_EQ(read_text(directory_ / "child.log"), "new\n");
}

// The transports ignore SIGPIPE in the coupler; the solver must start with the default.
TEST_F(ChildProcessTest, SignalDispositionsAreResetInTheChild) {
  std::signal(SIGPIPE, SIG_IGN);
  ChildOptions options = shell("");
  options.command = {"/bin/grep", "SigIgn", "/proc/self/status"};
  ChildProcess child(options);
  ASSERT_TRUE(child.wait_for_exit(10.0));
  EXPECT_EQ(read_text(directory_ / "child.log"), "SigIgn:\t0000000000000000\n");
}

TEST_F(ChildProcessTest, StopEndsTheWholeProcessGroup) {
  ChildProcess child(shell("sleep 60 & echo $! > background.pid; wait"));
  while (!std::filesystem::exists(directory_ / "background.pid") ||
         read_text(directory_ / "background.pid").empty())
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const pid_t background = std::stoi(read_text(directory_ / "background.pid"));
  ASSERT_TRUE(process_alive(background));
  child.stop(5.0);
  EXPECT_FALSE(child.running());
  EXPECT_FALSE(process_alive(child.pid()));
  for (int i = 0; i < 200 && process_alive(background); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_FALSE(process_alive(background));
}

TEST_F(ChildProcessTest, StopEscalatesToSigkill) {
  ChildProcess child(shell("trap '' TERM; echo ready; while :; do sleep 0.05; done"));
  while (read_text(directory_ / "child.log").empty())
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  child.stop(0.2);
  EXPECT_EQ(child.describe_exit(), "killed by signal 9 (Killed)");
}

TEST_F(ChildProcessTest, KillAllChildrenKillsEveryLiveChild) {
  ChildProcess first(shell("sleep 60"));
  ChildProcess second(shell("sleep 60"));
  kill_all_children();
  ASSERT_TRUE(first.wait_for_exit(5.0));
  ASSERT_TRUE(second.wait_for_exit(5.0));
  EXPECT_EQ(first.describe_exit(), "killed by signal 9 (Killed)");
  EXPECT_EQ(second.describe_exit(), "killed by signal 9 (Killed)");
}

TEST_F(ChildProcessTest, TheDestructorStopsTheChild) {
  pid_t pid;
  {
    ChildProcess child(shell("sleep 60"));
    pid = child.pid();
    EXPECT_TRUE(child.running());
  }
  EXPECT_FALSE(process_alive(pid));
}

TEST_F(ChildProcessTest, MissingOrUnusableExecutablesAreNamed) {
  auto options = shell("");
  options.command = {"no_such_solver_anywhere"};
  EXPECT_THROW(
      {
        try {
          ChildProcess child(options);
        } catch (const std::runtime_error& e) {
          EXPECT_NE(std::string(e.what()).find("'no_such_solver_anywhere' not found"),
                    std::string::npos)
              << e.what();
          throw;
        }
      },
      std::runtime_error);

  options.command = {"./bin/missing"};
  try {
    ChildProcess child(options);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find((directory_ / "bin/missing").string() + " does not exist"),
              std::string::npos)
        << e.what();
  }

  write_text(directory_ / "not_executable", "#!/bin/sh\n");
  options.command = {"./not_executable"};
  try {
    ChildProcess child(options);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("not_executable is not an executable file"),
              std::string::npos)
        << e.what();
  }
}

TEST_F(ChildProcessTest, AnExecFailureIsReported) {
  // Executable bit but no interpreter: passes the checks, fails in execve.
  write_text(directory_ / "broken", "#!/no/such/interpreter\n");
  std::filesystem::permissions(directory_ / "broken", std::filesystem::perms::owner_all);
  auto options = shell("");
  options.command = {"./broken"};
  try {
    ChildProcess child(options);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot start " + (directory_ / "broken").string()),
              std::string::npos)
        << e.what();
  }
}

TEST(FindExecutableTest, LooksInTheWorkingDirectoryFirstThenOnPath) {
  TemporaryDirectory directory;
  EXPECT_EQ(find_executable("sh", directory.path()).filename(), "sh");
  write_text(directory / "sh", "#!/bin/sh\n");
  std::filesystem::permissions(directory / "sh", std::filesystem::perms::owner_all);
  EXPECT_EQ(find_executable("sh", directory.path()), directory / "sh");
}

TEST(ReadLastLinesTest, ReturnsAtMostTheRequestedLines) {
  TemporaryDirectory directory;
  std::string text;
  for (int i = 1; i <= 30; ++i) text += "line " + std::to_string(i) + "\n";
  write_text(directory / "log", text);
  const std::string tail = read_last_lines(directory / "log", 20);
  EXPECT_EQ(tail.substr(0, 8), "line 11\n");
  EXPECT_EQ(tail.substr(tail.size() - 7), "line 30");
  write_text(directory / "short", "only\n");
  EXPECT_EQ(read_last_lines(directory / "short", 20), "only");
  EXPECT_EQ(read_last_lines(directory / "missing", 20), "");
}

}  // namespace
}  // namespace cocopp
