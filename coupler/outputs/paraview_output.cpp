// settings.vtk_output: true: the interface for ParaView every step, as VTU files and a PVD time
// series (<name>.pvd, <name>_vtk/; VtkSeries).
#include <memory>

#include "coupler/outputs/run_output.hpp"
#include "coupler/results/vtk_series.hpp"

namespace cocopp {
namespace {

class ParaviewOutput : public RunOutput {
 public:
  explicit ParaviewOutput(const Settings& settings)
      : wanted_(settings.get<bool>("vtk_output", false)) {}

  bool active() const override { return wanted_; }
  void open(const OutputStart& start) override {
    series_ = std::make_unique<VtkSeries>(start.files.directory, start.files.vtk_series(),
                                          start.continue_after_step);
    x_ = start.x;
    y_ = start.y;
  }
  void write_step(const StepRecord& record) override {
    x_.set_data(record.x);
    y_.set_data(record.y);
    series_->write_step(record.step, record.time, vtk_parts(x_, y_));
  }
  std::vector<OutputFile> files() const override { return {{"ParaView", series_->collection()}}; }

 private:
  bool wanted_;
  std::unique_ptr<VtkSeries> series_;
  Interface x_, y_;  ///< the layouts, with the step's values
};

}  // namespace

COCOPP_REGISTER(RunOutputRegistry, "paraview", ParaviewOutput)

}  // namespace cocopp
