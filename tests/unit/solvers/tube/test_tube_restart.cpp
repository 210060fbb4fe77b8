// The tube models continue bit for bit from their restart data.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/data/restart_file.hpp"
#include "tests/support/temporary_directory.hpp"
#include "tests/unit/solvers/tube/tube_test_parameters.hpp"

namespace cocopp::tube {
namespace {

namespace fs = std::filesystem;
using cocopp::testing::TemporaryDirectory;

// A model restored from the restart data of step 5 continues as the model that never stopped.
template <class Model, class Input>
void expect_continues_exactly(Model& uninterrupted, Model& restarted, Input input) {
  for (int step = 1; step <= 5; ++step) {
    uninterrupted.initialize_step();
    uninterrupted.solve(input(step));
    uninterrupted.finalize_step();
  }
  const TemporaryDirectory directory;
  const fs::path file = directory / "model.restart";
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

TEST(TubeRestart, EveryTubeModelContinuesBitForBit) {
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
