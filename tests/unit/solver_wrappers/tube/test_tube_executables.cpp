// The tube solver executables answer --help without a coupler.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

namespace {

class TubeExecutable : public ::testing::TestWithParam<std::string> {};

TEST_P(TubeExecutable, HelpExitsWithZero) {
  const std::string command = GetParam() + " --help > /dev/null";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
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
