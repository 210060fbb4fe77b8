// The tube solver executables answer --help and --check without a coupler.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>

#include "tests/support/temporary_directory.hpp"

namespace {

using cocopp::testing::read_text;
using cocopp::testing::TemporaryDirectory;
using cocopp::testing::write_text;

class TubeExecutable : public ::testing::TestWithParam<std::string> {
 protected:
  /// The exit code of `command` (-1 if it did not exit normally).
  static int exit_code(const std::string& command) {
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  /// An example's input file for this executable.
  std::filesystem::path example_input() const {
    static const std::map<std::string, std::string> files = {
        {"flow", "flow_structure/flow/tube_flow.yaml"},
        {"structure", "flow_structure/structure/tube_structure.yaml"},
        {"ringmodel", "flow_ringmodel/structure/tube_ringmodel.yaml"}};
    return std::filesystem::path(COCOPP_TUBE_EXAMPLES_DIR) / files.at(solver());
  }
  std::string solver() const { return GetParam().substr(GetParam().rfind('-') + 1); }
};

TEST_P(TubeExecutable, HelpExitsWithZero) {
  EXPECT_EQ(exit_code(GetParam() + " --help > /dev/null"), 0);
}

// `cocopp check` asks the executable itself (ProcessSolverWrapper::check_solver_input).
TEST_P(TubeExecutable, CheckAcceptsTheExampleInputAndNamesTheLineOfAMistake) {
  TemporaryDirectory directory;
  const auto output = directory / "output.txt";
  const std::string check = GetParam() + " --check ";
  EXPECT_EQ(exit_code(check + example_input().string() + " > " + output.string()), 0);
  EXPECT_EQ(read_text(output), example_input().string() + ": OK\n");

  const auto input = directory / "input.yaml";
  write_text(input, read_text(example_input()) + "no_such_key: 1\n");
  EXPECT_EQ(exit_code(check + input.string() + " 2> " + output.string()), 1);
  EXPECT_NE(read_text(output).find(input.string() + ":"), std::string::npos) << read_text(output);
  EXPECT_NE(read_text(output).find("'no_such_key'"), std::string::npos) << read_text(output);
}

// The paths come from CMake ($<TARGET_FILE:...>), so the test runs the executables it was
// built with.
INSTANTIATE_TEST_SUITE_P(Solvers, TubeExecutable,
                         ::testing::Values(COCOPP_TUBE_FLOW_EXECUTABLE,
                                           COCOPP_TUBE_STRUCTURE_EXECUTABLE,
                                           COCOPP_TUBE_RINGMODEL_EXECUTABLE),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           const std::string prefix = "cocopp-tube-";
                           const std::string& path = info.param;
                           return path.substr(path.rfind(prefix) + prefix.size());
                         });

}  // namespace
