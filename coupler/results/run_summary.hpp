#pragma once
// The JSON summary of a run: how it ended and where the time went, small enough to read by eye
// or to compare between runs. The keys are documented in docs/results.md.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

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
  void finish(bool completed, const std::string& status, const std::string& message,
              double total_wall_time, const std::vector<double>& total_solver_times,
              double total_coupler_time);

  /// Before finish(): status "running" and the times summed over the steps added so far.
  nlohmann::json to_json() const;

  /// Writes to_json() indented, atomically: readers see the old file or the new one, never a
  /// partial one. Creates the directory. Throws std::runtime_error on failure.
  void write(const std::filesystem::path& file) const;

 private:
  void check_solver_times(const std::vector<double>& times, const char* what) const;
  nlohmann::json solver_times_json() const;

  RunDescription run_;
  std::vector<int> steps_;
  std::vector<int> iterations_;
  std::vector<std::vector<double>> residuals_;
  std::vector<int> unconverged_steps_;
  std::vector<std::string> warnings_;  ///< "step 3: ...", from StepRecord::warnings

  bool completed_ = false;
  std::string status_ = "running";
  std::string message_;
  double wall_time_ = 0;
  std::vector<double> solver_times_;
  double coupler_time_ = 0;
  double iteration_coupler_time_ = 0;  ///< sum of the steps' coupler_time
};

}  // namespace cocopp
