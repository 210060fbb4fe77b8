#pragma once
// SummaryOutput: the run's summary (<name>.summary.json, RunSummary) as an output; also the
// run's own account of its steps, which Run reads (unconverged steps, steps completed) and
// cocopp bench gets back. Not a case-file choice: every run has one, opened with the run and
// closed last, so that it records every other output's failure to close.
#include "coupler/outputs/run_output.hpp"
#include "coupler/results/run_summary.hpp"

namespace cocopp {

class SummaryOutput : public RunOutput {
 public:
  SummaryOutput(RunDescription run, RunFiles files)
      : summary_(std::move(run)), path_(files.summary()) {}

  void open(const OutputStart& /*start*/) override {}
  void write_step(const StepRecord& record) override { summary_.add_step(record); }
  void close(const RunEnd& end) override {
    summary_.finish(end.outcome, end.wall_time, end.solver_times, end.coupler_time);
    summary_.set_steps_written(end.steps_written);
    summary_.write(path_);
  }
  std::vector<OutputFile> files() const override { return {{"summary", path_}}; }

  const RunSummary& summary() const { return summary_; }

 private:
  RunSummary summary_;
  std::filesystem::path path_;
};

}  // namespace cocopp
