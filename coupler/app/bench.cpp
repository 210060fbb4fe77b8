// `cocopp bench`: read the bench file (bench_file), write and validate every run
// (bench_preparation), run them in turn, compare them with their references (bench_comparison)
// and report (bench_report).
#include "coupler/app/bench.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>

#include "coupler/app/bench_comparison.hpp"
#include "coupler/app/bench_file.hpp"
#include "coupler/app/bench_preparation.hpp"
#include "coupler/app/bench_report.hpp"
#include "coupler/app/run.hpp"

namespace cocopp {

namespace {

/// Run every case in turn; returns false if the bench has to stop (interrupt, no reference).
bool run_all(const BenchFile& bench, const std::vector<PlannedRun>& runs,
             std::vector<BenchRow>& rows, const BenchOptions& options) {
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const std::string name = run_label(runs[i].case_name, runs[i].name);
    if (options.quiet)
      fmt::print("bench run {:>{}} of {}: {:<28} ", i + 1, std::to_string(runs.size()).size(),
                 runs.size(), name);
    else
      fmt::print("\n=== bench run {} of {}: {} ===\n", i + 1, runs.size(), name);
    std::fflush(stdout);
    RunOptions run_options;
    run_options.quiet = true;
    run_options.silent = options.quiet;
    run_options.restart = run_options.fresh_coupling = bench.start_from_state;
    const RunReport report = run_case(runs[i].case_file, run_options);
    BenchRow row = make_row(runs[i], report);
    if (options.quiet)
      fmt::print("{} after {} steps, {} it/step, {:.3f} s\n", row.outcome, row.steps_completed,
                 std::isfinite(row.average_iterations)
                     ? fmt::format("{:.2f}", row.average_iterations)
                     : std::string("-"),
                 std::isfinite(row.wall_time) ? row.wall_time : 0.0);
    // A solver names its input file relative to its directory: say which copy it read.
    if (report.outcome.status == RunStatus::kSolverFailed && !runs[i].changed_inputs.empty())
      add_note(row, "input changed by the bench: " + runs[i].changed_inputs);
    rows.push_back(row);
    if (report.outcome.status == RunStatus::kInterrupted) return false;
    if (row.name == kReferenceName && row.steps_completed == 0) {
      fmt::print(stderr, "error: the reference run {} computed no time step: {}\n", label(row),
                 row.message);
      return false;
    }
  }
  return true;
}

}  // namespace

int run_bench(const fs::path& bench_file, const BenchOptions& options) {
  BenchFile bench;
  std::vector<PlannedRun> runs;
  try {
    bench = read_bench_file(bench_file);
    fs::create_directories(bench.output_directory);
    runs = prepare_runs(bench);
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return 2;
  }
  std::vector<BenchRow> rows;
  const bool finished = run_all(bench, runs, rows, options);
  compare_with_references(bench, runs, rows);
  print_table(rows);
  const nlohmann::json reference = describe_references(bench);
  write_outputs(bench, reference, rows);
  fmt::print("\nreference: {}\ntable    : {}\n",
             reference.is_string() ? reference.get<std::string>() : "one per case (bench.json)",
             (bench.output_directory / "bench.csv").string());
  if (bench.reference == ReferenceKind::kNone)
    fmt::print("no plot of error against time: reference: none\n");
  else if (options.plot && finished)
    plot(bench);
  return finished ? 0 : 1;
}

}  // namespace cocopp
