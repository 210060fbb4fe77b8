#pragma once
// Helpers for end-to-end tests: run the cocopp executable on a copy of an example.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/support/temporary_directory.hpp"

namespace cocopp::testing {

struct CommandResult {
  int exit_code = -1;
  std::string output;  ///< stdout and stderr together
};

/// `cocopp run` went through every step: completed (0) or stalled (3: steps accepted at the
/// iteration limit above the solvers' noise, which the tests whose runs may stall accept).
inline bool went_through(const CommandResult& run) {
  return run.exit_code == 0 || run.exit_code == 3;
}

/// Run `command` through the shell, capturing its output.
CommandResult run_command(const std::string& command);
/// `cocopp <arguments>` with the built executable.
CommandResult run_cocopp(const std::string& arguments);
/// A fresh copy of examples/<example> in a temporary directory: what the example ships, without
/// what runs of it left in the checkout (results/, output/, restart/, logs, locks, FIFOs).
std::filesystem::path copy_example(const std::string& example, const std::string& tag);
nlohmann::json read_json(const std::filesystem::path& file);
/// All values of a dataset of a results (or state) file, flattened (ResultsReader).
std::vector<double> read_dataset(const std::filesystem::path& file, const std::string& name);
/// ||a - b|| / ||a||: how far a run's dataset (read_dataset) is from a reference run's.
double relative_difference(const std::vector<double>& a, const std::vector<double>& b);
/// Make an example's case stop its steps on both solvers' reports (solver_coupling_convergence
/// of solver 0 and 1) instead of its relative_norm 1e-6.
void use_solver_coupling_convergence(const std::filesystem::path& case_file);
/// Replace the first occurrence of `from` in a file (a failed test if it is not there).
void edit(const std::filesystem::path& file, const std::string& from, const std::string& to);

}  // namespace cocopp::testing
