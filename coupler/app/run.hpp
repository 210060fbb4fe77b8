#pragma once
// `cocopp run`: build a case, start its solvers, march in time, write results.
#include <filesystem>
#include <optional>

#include "coupler/results/run_outcome.hpp"
#include "coupler/results/run_summary.hpp"

namespace cocopp {

struct RunOptions {
  bool quiet = false;  ///< no progress lines (header and summary are still printed)
  /// Nothing printed: the caller reports the outcome (cocopp bench --quiet). Errors before the
  /// run starts (an invalid case) are still printed.
  bool silent = false;
  bool verbose = false;  ///< also one line per coupling iteration
  bool restart = false;  ///< continue from the saved state (load_case's `restart`)
  /// With restart: the coupled solver's own memory starts afresh (only the predictor's history
  /// is taken), so that a run can be continued with another coupled solver.
  bool fresh_coupling = false;
};

/// What a run of a case gives its caller (the command, cocopp bench): how it ended and its
/// summary, without reading its files back.
struct RunReport {
  RunOutcome outcome;
  std::optional<RunSummary> summary;   ///< absent when the case never started (invalid case)
  std::filesystem::path results_file;  ///< <results_directory>/<name>.h5 (absent if never started)
};

/// Run a case file: print the header, one progress line per step and the summary, write the
/// results. outcome.exit_code() is the process exit code.
RunReport run_case(const std::filesystem::path& case_file, const RunOptions& options);

/// `cocopp check`: build and validate a case without starting any solver.
int check_case(const std::filesystem::path& case_file);

}  // namespace cocopp
