#pragma once
// `cocopp bench`, part 2: the runs a bench file asks for, each a copy of the base case's
// directory with its own case.yaml and solver inputs, written and validated before the first run.
#include <filesystem>
#include <string>
#include <vector>

#include "coupler/app/bench_file.hpp"

namespace cocopp {

struct PlannedRun {
  std::string case_name;
  std::string name;
  fs::path case_file;
  std::string changed_inputs;  ///< input files changed by solver_inputs, and from where
  /// start_from_state: the run continues a saved state; its time is that of its steps (the
  /// solvers' restart, e.g. ccx replaying the saved steps, is no part of the method's cost).
  bool from_state = false;
};

/// Write <output_directory>/[<case>/]<name>/ for every run (the reference first in each case)
/// and validate each case, so that a mistake in the last variant is found before the first run.
/// Throws CaseError.
std::vector<PlannedRun> prepare_runs(const BenchFile& bench);

}  // namespace cocopp
