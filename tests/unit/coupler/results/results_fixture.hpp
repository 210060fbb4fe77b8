#pragma once
// A small run shared by the results tests: interfaces of two model parts, step records with
// ragged residual histories, and data that differs per step, point and component. The tests
// read the files back with ResultsReader (and with h5py).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "core/data/interface.hpp"
#include "coupler/results/results_reader.hpp"
#include "coupler/results/results_writer.hpp"
#include "coupler/results/step_record.hpp"

namespace cocopp::test {

inline std::shared_ptr<ModelPart> model_part(const std::string& name, int points, double z0) {
  auto part = std::make_shared<ModelPart>();
  part->name = name;
  part->coordinates.resize(points, 3);
  for (int i = 0; i < points; ++i) {
    part->ids.push_back(100 * (name.size()) + i);
    part->coordinates.row(i) << 0.005, 0.0, z0 + 0.01 * i;
  }
  return part;
}

struct Interfaces {
  Interface x, y;
};

/// x: displacement on "wall" (4 points) and "inlet" (2); y: pressure and traction on "wall",
/// pressure on "inlet".
inline Interfaces make_interfaces() {
  const auto wall = model_part("wall", 4, 0.0);
  const auto inlet = model_part("inlet", 2, -0.01);
  return {Interface({{wall, {"displacement"}}, {inlet, {"displacement"}}}),
          Interface({{wall, {"pressure", "traction"}}, {inlet, {"pressure"}}})};
}

/// Distinct values for every step and index, so a value in the wrong row or place shows.
inline void fill(Interfaces& interfaces, int step) {
  Eigen::VectorXd x(interfaces.x.size()), y(interfaces.y.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = 1e-3 * step + 1e-6 * i;
  for (Eigen::Index i = 0; i < y.size(); ++i) y[i] = 1000.0 * step - i;
  interfaces.x.set_data(x);
  interfaces.y.set_data(y);
}

inline RunDescription make_run(int steps) {
  RunDescription run;
  run.case_file = "examples/tube/case.yaml";
  run.coupled_solver = "iqni";
  run.solver_names = {"tube_flow", "tube_structure"};
  run.delta_t = 0.01;
  run.timestep_start = 0;
  run.number_of_timesteps = steps;
  return run;
}

/// Step 2 is accepted unconverged; iterations cycle 2, 3, 1, ...
inline StepRecord make_record(int step) {
  StepRecord r;
  r.step = step;
  r.time = 0.01 * step;
  r.iterations = 1 + (step + 1) % 3;
  for (int i = 0; i < r.iterations; ++i) r.residual_norms.push_back(std::pow(10.0, -i) / step);
  r.wall_time = 0.1 * step;
  r.solver_times = {0.03 * step, 0.05 * step};
  r.coupler_time = r.wall_time - r.solver_times[0] - r.solver_times[1];
  r.converged = step != 2;
  return r;
}

/// Writes steps 1..steps; closes with `status` unless it is empty (then the file stays open
/// and the writer is returned).
inline std::unique_ptr<ResultsWriter> write_run(const std::filesystem::path& file, int steps,
                                                const std::string& status = "completed") {
  Interfaces interfaces = make_interfaces();
  auto writer = std::make_unique<ResultsWriter>(file, make_run(steps), interfaces.x, interfaces.y);
  for (int step = 1; step <= steps; ++step) {
    fill(interfaces, step);
    writer->write_step(make_record(step), interfaces.x, interfaces.y);
  }
  if (!status.empty()) writer->close(status, "all " + std::to_string(steps) + " steps done");
  return writer;
}

/// A fresh directory for one test, under the test's working directory (kept for inspection).
inline std::filesystem::path test_directory() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const auto dir = std::filesystem::current_path() / "results_test_output" /
                   (std::string(info->test_suite_name()) + "." + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace cocopp::test
