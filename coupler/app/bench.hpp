#pragma once
// `cocopp bench`: run one base case with several coupled-solver variants and compare them:
// iterations, run time and the error against a reference solution (docs/bench.md).
#include <filesystem>

namespace cocopp {

struct BenchOptions {
  bool plot = true;    ///< draw bench.png with scripts/plot_bench.py
  bool quiet = false;  ///< one line per run instead of each run's header and summary
};

/// Run a benchmark file. Returns the process exit code: 0 every run was made (a diverging
/// variant is a result, not a failure), 1 the bench stopped (interrupt, reference failed),
/// 2 the bench file or one of the cases it makes is invalid.
int run_bench(const std::filesystem::path& bench_file, const BenchOptions& options);

}  // namespace cocopp
