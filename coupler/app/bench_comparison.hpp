#pragma once
// `cocopp bench`, part 3: comparing runs. A row per run from its typed report (how it ended,
// iterations, times), and its error against its case's reference, read with ResultsReader.
#include <limits>
#include <string>
#include <vector>

#include "coupler/app/bench_file.hpp"
#include "coupler/app/bench_preparation.hpp"
#include "coupler/app/run.hpp"

namespace cocopp {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// One row of the table, bench.csv and bench.json.
struct BenchRow {
  std::string case_name;  ///< empty without `cases`
  std::string name;
  std::string coupled_solver;
  std::string status = "not_run";
  std::string message;
  bool completed = false;
  int steps_completed = 0;
  double average_iterations = kNaN;
  int maximum_iterations = 0;
  long solver_calls = 0;
  double wall_time = kNaN;
  double coupler_time = kNaN;
  double solver_time = kNaN;  ///< both solvers together, the whole run
  double displacement_error = kNaN;
  double pressure_error = kNaN;
  std::string note;
  /// converged, stalled (steps accepted at the iteration limit), diverged, solver_failed, ...
  std::string outcome;
  std::string reason;  ///< why it diverged or stalled, e.g. "residual growth in step 3"
  int unconverged_steps = 0;
};

/// The row of a run from what run_case reported.
BenchRow make_row(const PlannedRun& run, const RunReport& report);

void add_note(BenchRow& row, const std::string& note);

/// Fill the errors of every row against the reference of its case (nothing for
/// `reference: none`). rows[i] belongs to runs[i]. A reference that cannot be read is a warning.
void compare_with_references(const BenchFile& bench, const std::vector<PlannedRun>& runs,
                             std::vector<BenchRow>& rows);

}  // namespace cocopp
