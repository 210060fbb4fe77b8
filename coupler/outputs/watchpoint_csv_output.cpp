// settings.watchpoints: each watchpoint's values every step as a CSV file
// (<name>_watchpoint_<point>.csv; WatchpointCsv). The HDF5 results file holds them too.
#include <memory>

#include "coupler/outputs/run_output.hpp"
#include "coupler/results/watchpoint_csv.hpp"

namespace cocopp {
namespace {

class WatchpointCsvOutput : public RunOutput {
 public:
  // The watchpoints themselves are read with the case (Watchpoints): the run samples them.
  explicit WatchpointCsvOutput(const Settings& settings) : wanted_(settings.has("watchpoints")) {}

  bool active() const override { return wanted_; }
  void open(const OutputStart& start) override {
    csv_ =
        std::make_unique<WatchpointCsv>(start.files, start.watchpoints, start.continue_after_step);
    values_ = start.watchpoints;
  }
  void write_step(const StepRecord& record) override {
    values_.set_data(record.watchpoints);
    csv_->write_step(record.step, record.time, values_);
  }
  std::vector<OutputFile> files() const override {
    std::vector<OutputFile> files;
    for (const auto& file : csv_->files()) files.emplace_back("watchpoint", file);
    return files;
  }

 private:
  bool wanted_;
  std::unique_ptr<WatchpointCsv> csv_;
  Interface values_;  ///< the watchpoints' layout, with the step's values
};

}  // namespace

COCOPP_REGISTER(RunOutputRegistry, "watchpoint_csv", WatchpointCsvOutput)

}  // namespace cocopp
