#pragma once
// Runs of a tube example with its time step, substeps and time interpolation changed, for the
// substeps tests (test_substeps.cpp, test_coupling_accuracy.cpp), and how to compare them.
#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include "tests/integration/run_helpers.hpp"

namespace cocopp::testing {

inline int total_iterations(const nlohmann::json& summary) {
  int total = 0;
  for (const auto& iterations : summary["iterations_per_step"]) total += iterations.get<int>();
  return total;
}

/// A number as the case file takes it, to the last digit.
inline std::string number(double value) {
  std::ostringstream text;
  text << std::setprecision(17) << value;
  return text.str();
}

struct Variant {
  double delta_t;
  int steps;
  int flow_substeps = 1, structure_substeps = 1;
  std::string interpolation = "linear";
  bool time_average = true;
};

/// A copy of `example` run as `variant` says, converged to a relative 1e-9 (1e-11 for the ring
/// model); its directory.
inline std::filesystem::path run_variant(const std::string& example, const std::string& tag,
                                         const Variant& variant, double tolerance = 1e-9) {
  const std::filesystem::path dir = copy_example(example, tag);
  const std::filesystem::path case_file = dir / "case.yaml";
  const std::string tube_steps = example == "tube/flow_structure"
                                     ? "  delta_t: 1.0e-4            # s\n"
                                       "  number_of_timesteps: 100\n"
                                     : "  delta_t: 0.01              # s\n"
                                       "  number_of_timesteps: 100\n";
  edit(case_file, tube_steps,
       "  delta_t: " + number(variant.delta_t) +
           "\n  number_of_timesteps: " + std::to_string(variant.steps) + "\n");
  edit(case_file, "  type: iqni\n",
       "  type: iqni\n  time_interpolation: " + variant.interpolation + "\n  time_average: " +
           (variant.time_average ? "true" : "false") + "\n  divergence: {growth_iterations: 0}\n");
  edit(case_file, "tolerance: 1.0e-6", "tolerance: " + number(tolerance));
  edit(case_file, "maximum: 15", "maximum: 100");
  if (variant.flow_substeps > 1)
    edit(case_file, "    name: flow\n",
         "    name: flow\n    substeps: " + std::to_string(variant.flow_substeps) + "\n");
  if (variant.structure_substeps > 1)
    edit(case_file, "    name: structure\n",
         "    name: structure\n    substeps: " + std::to_string(variant.structure_substeps) + "\n");
  // Converged to a relative 1e-9, some steps end at the limit near the solvers' noise.
  const CommandResult run = run_cocopp("run -q " + case_file.string());
  EXPECT_TRUE(went_through(run)) << run.exit_code << "\n" << run.output;
  return dir;
}

/// The radial displacement of a run at every `every`-th step, flattened.
inline std::vector<double> radial(const std::filesystem::path& dir, int every = 1,
                                  std::size_t steps = 0) {
  const auto all = read_dataset(dir / "results" / "case.h5", "x/wall/displacement");
  const std::size_t cells = 100, stored = all.size() / (3 * cells);
  std::vector<double> values;
  for (std::size_t step = static_cast<std::size_t>(every) - 1;
       step < stored && (steps == 0 || values.size() < steps * cells);
       step += static_cast<std::size_t>(every))
    for (std::size_t cell = 0; cell < cells; ++cell)
      values.push_back(all[3 * (step * cells + cell) + 1]);
  return values;
}

}  // namespace cocopp::testing
