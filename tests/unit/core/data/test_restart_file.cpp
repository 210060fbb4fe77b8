// Restart files (named arrays as hex floats, the tube solvers' and the calculix wrapper's): exact
// round trips and errors that name the file.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>

#include "core/data/restart_file.hpp"
#include "tests/support/error_message.hpp"
#include "tests/support/temporary_directory.hpp"

namespace cocopp {
namespace {

namespace fs = std::filesystem;
using cocopp::testing::TemporaryDirectory;

TEST(RestartFile, HoldsEveryDoubleExactly) {
  Eigen::VectorXd values(7);
  values << 1.0 / 3.0, -0.0, std::numeric_limits<double>::denorm_min(),
      std::numeric_limits<double>::max(), -1.2345678901234567e-300, std::nextafter(1.0, 2.0), 0.1;
  const TemporaryDirectory directory;
  const fs::path file = directory / "exact.restart";
  write_restart_file(file, "tube_flow", 12, {{"a", values}, {"empty", Eigen::VectorXd()}});
  const RestartData data = read_restart_file(file, "tube_flow", 12);
  ASSERT_EQ(data.at("a").size(), values.size());
  for (Eigen::Index i = 0; i < values.size(); ++i) {
    EXPECT_EQ(data.at("a")[i], values[i]) << i;
    EXPECT_EQ(std::signbit(data.at("a")[i]), std::signbit(values[i])) << i;
  }
  EXPECT_EQ(data.at("empty").size(), 0);
  EXPECT_FALSE(fs::exists(file.string() + ".writing"));
  EXPECT_EQ(restart_file_name("tube_flow", 12), fs::path("restart/tube_flow_000012.restart"));
}

TEST(RestartFile, ErrorsNameTheFileAndWhatIsWrong) {
  using cocopp::testing::error_message;
  const TemporaryDirectory directory;
  const fs::path file = directory / "errors.restart";
  const auto read_error = [&](const std::string& solver, int step) {
    return error_message<std::runtime_error>([&] { read_restart_file(file, solver, step); });
  };
  fs::remove(file);
  EXPECT_NE(read_error("tube_flow", 3).find(file.string() + ": not found"), std::string::npos);
  write_restart_file(file, "tube_flow", 3, {{"a", Eigen::VectorXd::Ones(2)}});
  EXPECT_NE(read_error("tube_structure", 3)
                .find("holds tube_flow after step 3, expected "
                      "tube_structure after step 3"),
            std::string::npos);
  EXPECT_NE(read_error("tube_flow", 4).find("expected tube_flow after step 4"), std::string::npos);
  const RestartData data = read_restart_file(file, "tube_flow", 3);
  EXPECT_NE(error_message<std::runtime_error>([&] {
              restart_array(data, "a", 5, file);
            }).find("'a' has 2 values, this model needs 5"),
            std::string::npos);
  EXPECT_NE(error_message<std::runtime_error>([&] {
              restart_array(data, "b", 2, file);
            }).find("has no 'b'"),
            std::string::npos);
  std::ofstream(file, std::ios::app) << "c 2 0x1p+0 pear\n";
  EXPECT_NE(read_error("tube_flow", 3).find("line 5: 'pear' is not a number"), std::string::npos);
}

}  // namespace
}  // namespace cocopp
