// Restart files of the tube solvers: exact round trips, models that continue bit for bit from
// one, and errors that name the file.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/data/restart_file.hpp"
#include "tests/support/error_message.hpp"
#include "tests/unit/solver_wrappers/tube/tube_test_parameters.hpp"

namespace cocopp::tube {
namespace {

namespace fs = std::filesystem;

fs::path test_file(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("cocopp_restart_file_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

TEST(RestartFile, HoldsEveryDoubleExactly) {
  Eigen::VectorXd values(7);
  values << 1.0 / 3.0, -0.0, std::numeric_limits<double>::denorm_min(),
      std::numeric_limits<double>::max(), -1.2345678901234567e-300, std::nextafter(1.0, 2.0), 0.1;
  const fs::path file = test_file("exact.restart");
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
  const fs::path file = test_file("errors.restart");
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

// A model restored from the restart data of step 5 continues as the model that never stopped.
template <class Model, class Input>
void expect_continues_exactly(Model& uninterrupted, Model& restarted, Input input) {
  for (int step = 1; step <= 5; ++step) {
    uninterrupted.initialize_step();
    uninterrupted.solve(input(step));
    uninterrupted.finalize_step();
  }
  const fs::path file = test_file("model.restart");
  write_restart_file(file, "model", 5, uninterrupted.restart_data());
  restarted.restore(read_restart_file(file, "model", 5), file);
  for (int step = 6; step <= 10; ++step) {
    uninterrupted.initialize_step();
    restarted.initialize_step();
    const Eigen::VectorXd a = uninterrupted.solve(input(step));
    const Eigen::VectorXd b = restarted.solve(input(step));
    ASSERT_EQ(a.size(), b.size());
    for (Eigen::Index i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << "step " << step;
    uninterrupted.finalize_step();
    restarted.finalize_step();
  }
}

Eigen::VectorXd wave(int step, int cells, double amplitude) {
  Eigen::VectorXd values(cells);
  for (int i = 0; i < cells; ++i) values[i] = amplitude * std::sin(0.1 * i + 0.7 * step);
  return values;
}

TEST(RestartFile, EveryTubeModelContinuesBitForBit) {
  const double dt = 1e-4;
  TubeFlow flow(testing::reference_flow(20), dt),
      restarted_flow(testing::reference_flow(20), dt, 5);
  expect_continues_exactly(flow, restarted_flow, [](int step) { return wave(step, 20, 1e-5); });
  TubeStructure structure(testing::reference_structure(20), dt),
      restarted_structure(testing::reference_structure(20), dt, 5);
  expect_continues_exactly(structure, restarted_structure,
                           [](int step) { return wave(step, 20, 100.0); });
  TubeRingmodel rings(testing::reference_ringmodel(20)),
      restarted_rings(testing::reference_ringmodel(20), 5);
  expect_continues_exactly(rings, restarted_rings, [](int step) { return wave(step, 20, 100.0); });
}

}  // namespace
}  // namespace cocopp::tube
