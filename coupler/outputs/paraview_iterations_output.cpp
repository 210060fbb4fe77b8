// settings.vtk_iterations: [steps]: every coupling iteration of the chosen steps for ParaView,
// x, y and the residual r = x~ - x, as <name>_step<step>_iterations.pvd with the iteration
// number as its time (VtkSeries).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "coupler/outputs/run_output.hpp"
#include "coupler/results/vtk_series.hpp"

namespace cocopp {
namespace {

class ParaviewIterationsOutput : public RunOutput {
 public:
  explicit ParaviewIterationsOutput(const Settings& settings) {
    for (const double step : settings.get<std::vector<double>>("vtk_iterations", {})) {
      if (step < 1 || step != std::floor(step) || step > 1e9)
        settings.fail("vtk_iterations",
                      fmt::format("{:g} is not a time step number: list the steps (1, 2, ...) "
                                  "whose coupling iterations to write",
                                  step));
      steps_.push_back(static_cast<int>(step));
    }
  }

  bool active() const override { return !steps_.empty(); }
  void open(const OutputStart& start) override {
    files_ = start.files;
    x_ = start.x;
    y_ = start.y;
  }
  void write_step(const StepRecord& /*record*/) override {}
  bool wants_iterations() const override { return true; }
  void write_iteration(const IterationReport& report) override {
    if (std::find(steps_.begin(), steps_.end(), report.step) == steps_.end()) return;
    if (report.iteration == 1 || !series_)
      series_ =
          std::make_unique<VtkSeries>(files_.directory, files_.iteration_vtk_series(report.step));
    x_.set_data(*report.x);
    y_.set_data(*report.y);
    std::vector<VtkPart> parts = vtk_parts(x_, y_);
    Interface residual = x_;
    residual.set_data(*report.residual_vector);
    add_vtk_fields(parts, residual, "residual_");
    series_->write_step(report.iteration, report.iteration, parts);
  }

 private:
  std::vector<int> steps_;
  RunFiles files_;
  Interface x_, y_;                    ///< the layouts, with the iteration's values
  std::unique_ptr<VtkSeries> series_;  ///< the chosen step being computed
};

}  // namespace

COCOPP_REGISTER(RunOutputRegistry, "paraview_iterations", ParaviewIterationsOutput)

}  // namespace cocopp
