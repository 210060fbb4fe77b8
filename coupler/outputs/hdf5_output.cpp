// The HDF5 results file (<name>.h5, ResultsWriter; docs/results.md): every run writes it.
// settings.results_write_interval (s of wall time, default 0) keeps fast steps in memory and
// writes them together.
#include <memory>

#include "coupler/outputs/run_output.hpp"
#include "coupler/results/results_writer.hpp"

namespace cocopp {
namespace {

class Hdf5Output : public RunOutput {
 public:
  explicit Hdf5Output(const Settings& settings)
      : write_interval_(
            settings.get_in_range("results_write_interval", 0.0, Range::closed(0.0, 3600.0))) {}

  void open(const OutputStart& start) override {
    writer_ =
        start.continue_after_step >= 0
            ? std::make_unique<ResultsWriter>(start.files.results(), start.run, start.x, start.y,
                                              start.continue_after_step, start.watchpoints)
            : std::make_unique<ResultsWriter>(start.files.results(), start.run, start.x, start.y,
                                              start.watchpoints);
    writer_->set_write_interval(write_interval_);
  }
  void write_step(const StepRecord& record) override { writer_->write_step(record); }
  void flush() override { writer_->write_kept_steps(); }
  void close(const RunEnd& end) override {
    if (end.unfinished_step > 0)
      writer_->write_unfinished_step(end.unfinished_step, end.unfinished_time,
                                     end.unfinished_residuals);
    writer_->close(to_string(end.outcome.status), end.outcome.message);
  }
  std::vector<OutputFile> files() const override { return {{"results", writer_->path()}}; }
  std::optional<int> steps_written() const override { return writer_->steps_written(); }

 private:
  double write_interval_;
  std::unique_ptr<ResultsWriter> writer_;
};

}  // namespace

COCOPP_REGISTER(RunOutputRegistry, "hdf5", Hdf5Output)

}  // namespace cocopp
