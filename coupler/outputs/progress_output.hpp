#pragma once
// ProgressOutput: what a run prints while it goes. One line per time step (the residual, the
// step's wall time and the time left at the pace so far), the first steps' warnings, and with
// --verbose one line per coupling iteration. Not a case-file choice: the command line's
// (cocopp run -q, -v; cocopp bench runs print nothing).
#include <chrono>

#include "coupler/outputs/run_output.hpp"

namespace cocopp {

class ProgressOutput : public RunOutput {
 public:
  /// `steps`: print a line per step; `iterations`: and per coupling iteration; `warnings`:
  /// print the first steps' warnings (all go to the summary).
  ProgressOutput(bool steps, bool iterations, bool warnings)
      : steps_(steps), iterations_(iterations), warnings_(warnings) {}

  void open(const OutputStart& start) override;
  void write_step(const StepRecord& record) override;
  bool wants_iterations() const override { return iterations_; }
  void write_iteration(const IterationReport& report) override;

 private:
  void print_warnings(const StepRecord& record);

  bool steps_, iterations_, warnings_;
  int first_ = 0, last_ = 0;  ///< the run's steps
  std::filesystem::path summary_;
  std::chrono::steady_clock::time_point start_;
  int steps_with_warnings_ = 0;
};

}  // namespace cocopp
