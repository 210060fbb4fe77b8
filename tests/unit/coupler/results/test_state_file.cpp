// The state file: a State tree written to HDF5 and read back exactly, and errors that name the
// file.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <filesystem>
#include <limits>

#include "coupler/results/state_file.hpp"
#include "tests/support/temporary_directory.hpp"

namespace cocopp {
namespace {

using cocopp::testing::TemporaryDirectory;

TEST(StateFile, HoldsTheTreeAndEveryDoubleExactly) {
  SavedState saved;
  saved.step = 12;
  saved.time = 1.2e-3;
  saved.coupled_solver = "iqni (omega 0.01, model ls)";
  saved.state.set("scalar", 1.0 / 3.0);
  const Eigen::VectorXd vector =
      Eigen::VectorXd::LinSpaced(4, -1.0, std::numeric_limits<double>::max());
  saved.state.set("vector", vector);
  const Eigen::MatrixXd columns = Eigen::MatrixXd::Random(5, 3);
  saved.state.group("model").set("columns", columns);
  saved.state.group("model").group("inner").set("denormal",
                                                std::numeric_limits<double>::denorm_min());
  TemporaryDirectory directory;
  const auto file = directory / "run.state.h5";
  write_state_file(file, saved);

  const SavedState read = read_state_file(file);
  EXPECT_EQ(read.step, 12);
  EXPECT_EQ(read.time, 1.2e-3);
  EXPECT_EQ(read.coupled_solver, saved.coupled_solver);
  EXPECT_EQ(read.state.scalar("scalar"), 1.0 / 3.0);
  EXPECT_EQ(read.state.vector("vector"), saved.state.vector("vector"));
  EXPECT_EQ(read.state.group("model").matrix("columns"),
            saved.state.group("model").matrix("columns"));
  EXPECT_EQ(read.state.group("model").group("inner").scalar("denormal"),
            std::numeric_limits<double>::denorm_min());
  EXPECT_FALSE(read.state.has_group("other"));
}

TEST(StateFile, AMissingFileIsNamed) {
  try {
    read_state_file("/nonexistent/dir/run.state.h5");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/run.state.h5"), std::string::npos);
  }
}

TEST(StateFile, AnArrayMissingFromTheStateIsNamedWithItsPath) {
  State state;
  state.group("model").set("v", 1.0);
  try {
    (void)state.group("model").matrix("w");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("model/w"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace cocopp
