#include "coupler/app/bench_comparison.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "coupler/results/results_reader.hpp"

namespace cocopp {

namespace {

using Fields = std::map<std::string, ResultsReader::Array>;  ///< one variable, by model part

/// What the error needs from a results file.
struct Results {
  double delta_t = kNaN;
  std::vector<int> steps;
  int restarted_after_step = 0;  ///< a continued file: the step its run started after
  Fields displacement;
  Fields pressure;
};

Results read_results(const fs::path& file) {
  const ResultsReader reader(file);
  Results r;
  r.delta_t = reader.delta_t();
  r.steps = reader.steps();
  if (reader.has_attribute("/", "restarted_after_step"))
    r.restarted_after_step = static_cast<int>(reader.number("/", "restarted_after_step"));
  r.displacement = reader.variable("x", "displacement");
  r.pressure = reader.variable("y", "pressure");
  return r;
}

/// ||v - r|| / ||r|| over every model part and every time step both runs have, after
/// `first_after` (a run continuing a saved state: its own steps); NaN if they share no step or
/// do not have the same parts and sizes. The reference may take `every` steps to one of the
/// run's (a finer delta_t): its step `every` s is the run's step s.
double relative_error(const Results& v, const Fields& variant, const Results& ref,
                      const Fields& reference, int first_after, int every) {
  if (reference.empty() || variant.size() != reference.size()) return kNaN;
  std::map<int, std::size_t> reference_row;
  for (std::size_t i = 0; i < ref.steps.size(); ++i) reference_row[ref.steps[i]] = i;
  double difference = 0.0, norm = 0.0;
  bool any = false;
  for (const auto& [part, r] : reference) {
    const auto found = variant.find(part);
    if (found == variant.end() || found->second.row_size() != r.row_size()) return kNaN;
    const ResultsReader::Array& f = found->second;
    const std::size_t row_size = r.row_size();
    for (std::size_t i = 0; i < v.steps.size(); ++i) {
      if (v.steps[i] <= first_after) continue;
      const auto row = reference_row.find(v.steps[i] * every);
      if (row == reference_row.end()) continue;
      const std::size_t a = i * row_size, b = row->second * row_size;
      if (a + row_size > f.values.size() || b + row_size > r.values.size()) continue;
      any = true;
      for (std::size_t k = 0; k < row_size; ++k) {
        const double d = f.values[a + k] - r.values[b + k];
        difference += d * d;
        norm += r.values[b + k] * r.values[b + k];
      }
    }
  }
  if (!any) return kNaN;
  if (norm == 0.0) return difference == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
  return std::sqrt(difference / norm);
}

void compute_errors(BenchRow& row, const fs::path& results_file, const Results& reference,
                    bool from_state) {
  if (!fs::exists(results_file)) return add_note(row, "no results file");
  Results v;
  try {
    v = read_results(results_file);
  } catch (const std::exception& e) {
    return add_note(row, e.what());
  }
  if (v.steps.empty()) return;
  // A reference at a finer step (a fully resolved run) is compared at the run's steps.
  const double ratio = v.delta_t / reference.delta_t;
  const int every = static_cast<int>(std::lround(ratio));
  if (every < 1 || !(std::abs(ratio - every) <= 1e-9 * ratio))
    return add_note(row, fmt::format("delta_t {:g} is not a whole multiple of the reference's "
                                     "{:g}: no error",
                                     v.delta_t, reference.delta_t));
  // A run continuing a saved state: the steps before it are the base run's in every file.
  const int first_after = from_state ? v.restarted_after_step : std::numeric_limits<int>::min();
  row.displacement_error =
      relative_error(v, v.displacement, reference, reference.displacement, first_after, every);
  row.pressure_error =
      relative_error(v, v.pressure, reference, reference.pressure, first_after, every);
  if (std::isnan(row.displacement_error)) add_note(row, "no step in common with reference");
}

}  // namespace

void add_note(BenchRow& row, const std::string& note) {
  row.note += (row.note.empty() ? "" : "; ") + note;
}

BenchRow make_row(const PlannedRun& run, const RunReport& report) {
  BenchRow row;
  row.case_name = run.case_name;
  row.name = run.name;
  const RunOutcome& outcome = report.outcome;
  row.status = to_string(outcome.status);
  row.message = outcome.message;
  row.completed = ran_all_steps(outcome.status);
  // converged, stalled, diverged, solver_failed, ...: the run's status, except that a run with
  // every step converged is "converged" in the bench's terms.
  row.outcome = outcome.status == RunStatus::kCompleted ? "converged" : row.status;
  row.reason = outcome.reason;
  if (!report.summary) return row;
  const RunSummary& summary = *report.summary;
  row.coupled_solver = summary.run().coupled_solver;
  row.steps_completed = summary.steps_completed();
  row.average_iterations = summary.average_iterations();
  const auto& iterations = summary.iterations_per_step();
  if (!iterations.empty())
    row.maximum_iterations = *std::max_element(iterations.begin(), iterations.end());
  row.solver_calls = 2 * summary.total_iterations();  // each solver once per coupling iteration
  row.wall_time = run.from_state ? summary.steps_wall_time() : summary.wall_time();
  row.coupler_time = summary.step_coupler_time();
  row.solver_time = summary.solver_time();
  // Steps at the limit with the residual at the solvers' noise are no stall (the run's
  // status says the same), but the note counts them.
  const auto at_noise = static_cast<int>(summary.steps_at_noise().size());
  row.unconverged_steps = static_cast<int>(summary.unconverged_steps().size()) - at_noise;
  if (row.unconverged_steps > 0)
    add_note(row, fmt::format("{} step{} accepted unconverged at the iteration limit",
                              row.unconverged_steps, row.unconverged_steps == 1 ? "" : "s"));
  if (at_noise > 0)
    add_note(row, fmt::format("{} step{} at the iteration limit with the residual at the "
                              "solvers' noise",
                              at_noise, at_noise == 1 ? "" : "s"));
  return row;
}

void compare_with_references(const BenchFile& bench, const std::vector<PlannedRun>& runs,
                             std::vector<BenchRow>& rows) {
  if (bench.reference == ReferenceKind::kNone) return;
  for (const BenchCase& c : bench.cases) {
    const fs::path reference = reference_of(bench, c.name);
    try {
      const Results reference_results = read_results(reference);
      for (std::size_t i = 0; i < rows.size(); ++i)
        if (rows[i].case_name == c.name)
          compute_errors(rows[i], runs[i].case_file.parent_path() / "results" / "case.h5",
                         reference_results, runs[i].from_state);
    } catch (const std::exception& e) {
      fmt::print(stderr, "warning: cannot read the reference {}: {}\n", reference.string(),
                 e.what());
    }
  }
}

}  // namespace cocopp
