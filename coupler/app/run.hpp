#pragma once
// `cocopp run`: build a case, start its solvers, march in time, write results.
#include <filesystem>

namespace cocopp {

struct RunOptions {
  bool quiet = false;  ///< no progress lines (header and summary are still printed)
};

/// Run a case file. Returns the process exit code: 0 completed, 1 the run stopped (diverged,
/// solver failed, interrupted), 2 the case file is invalid.
int run_case(const std::filesystem::path& case_file, const RunOptions& options);

/// `cocopp check`: build and validate a case without starting any solver.
int check_case(const std::filesystem::path& case_file);

}  // namespace cocopp
