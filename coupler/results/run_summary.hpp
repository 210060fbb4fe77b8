#pragma once
// The JSON summary of a run: how it ended and where the time went, small enough to read by eye
// or to compare between runs. The keys are documented in docs/results.md.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "coupler/results/run_outcome.hpp"
#include "coupler/results/step_record.hpp"

namespace cocopp {

class RunSummary {
 public:
  explicit RunSummary(RunDescription run);

  /// Throws std::invalid_argument unless record.solver_times has one entry per solver.
  void add_step(const StepRecord& record);

  /// How the run ended, with the totals over the whole run (including start-up and
  /// finalisation, which the steps do not cover). Throws std::invalid_argument unless
  /// total_solver_times has one entry per solver.
  void finish(const RunOutcome& outcome, double total_wall_time,
              const std::vector<double>& total_solver_times, double total_coupler_time);

  /// Before finish(): status "running" and the times summed over the steps added so far.
  nlohmann::json to_json() const;

  const RunDescription& run() const { return run_; }
  const std::vector<int>& iterations_per_step() const { return iterations_; }
  /// Steps accepted at the iteration limit, those with the residual at the solvers' noise
  /// among them (StepRecord::at_noise).
  const std::vector<int>& unconverged_steps() const { return unconverged_steps_; }
  const std::vector<int>& steps_at_noise() const { return steps_at_noise_; }
  /// The steps of this run the results file holds (none: no results file): fewer than
  /// steps_completed() where the file could not take them (a full disk).
  void set_steps_written(std::optional<int> steps) { steps_written_ = steps; }
  int steps_completed() const { return static_cast<int>(steps_.size()); }
  long total_iterations() const;
  /// NaN before the first step.
  double average_iterations() const;
  double wall_time() const { return wall_time_; }
  /// The wall time inside the steps only (no start-up: e.g. a restart's replay).
  double steps_wall_time() const { return steps_wall_time_; }
  /// The time spent in the solvers, summed over them (before finish(): inside the steps).
  double solver_time() const;
  /// The coupling algorithm's own time inside the steps (no start-up, no results I/O).
  double step_coupler_time() const { return iteration_coupler_time_; }

  /// Writes to_json() indented, atomically: readers see the old file or the new one, never a
  /// partial one. Creates the directory. Throws std::runtime_error on failure.
  void write(const std::filesystem::path& file) const;

 private:
  void check_solver_times(const std::vector<double>& times, const char* what) const;
  nlohmann::json solver_times_json() const;

  RunDescription run_;
  std::vector<int> steps_;
  std::vector<int> iterations_;
  std::vector<int> surrogate_iterations_;  ///< iqnism only: its surrogate's, per step
  std::vector<std::vector<double>> residuals_;
  std::vector<int> unconverged_steps_;
  std::vector<int> steps_at_noise_;
  std::optional<int> steps_written_;
  std::vector<std::string> warnings_;  ///< "step 3: ...", from StepRecord::warnings

  bool finished_ = false;
  RunOutcome outcome_;
  double wall_time_ = 0;
  double steps_wall_time_ = 0;
  std::vector<double> solver_times_;
  double coupler_time_ = 0;
  double iteration_coupler_time_ = 0;  ///< sum of the steps' coupler_time
};

}  // namespace cocopp
