// serial: the solvers one after the other, x~ = S(F(x)) (the serial scheme of CoCoNuT and
// preCICE). The unknown is x; S takes F's loads (or what a coupled solver that updates y too
// makes of them: LoadsUpdate).
//
// Substeps (waveform iteration, docs/coupling.md "Substeps"): where a solver takes k steps of
// its own per coupling time step, the unknown is x over the whole window, sampled at the ends
// of S's substeps; F gets x at the ends of its substeps (interpolated in time, Waveform), S gets
// F's loads at the ends of its own, and the iteration converges whole windows.
#include <memory>

#include "coupler/schemes/coupling_scheme.hpp"

namespace cocopp {
namespace {

/// `one` repeated for each of `samples` samples, parts named "<part> (substep j of k)": the
/// layout of a window's unknown, for the scaling's per-variable weights.
Interface repeated(const Interface& one, int samples) {
  if (samples == 1) return one;
  std::vector<Interface::Part> parts;
  for (int j = 1; j <= samples; ++j)
    for (const auto& part : one.parts()) {
      auto copy = std::make_shared<ModelPart>(*part.model_part);
      copy->name += " (substep " + std::to_string(j) + " of " + std::to_string(samples) + ")";
      parts.push_back({copy, part.variables});
    }
  return Interface(std::move(parts));
}

class SerialScheme : public CouplingScheme {
 public:
  SerialScheme(const Settings&, Parts parts) : CouplingScheme(std::move(parts)) {}

  std::vector<const Interface*> unknown_layouts() const override {
    return {windowed() ? &x_window_ : &x_};
  }
  Eigen::VectorXd unknown() const override { return windowed() ? x_window_.data() : x_.data(); }
  void set_unknown(const Eigen::VectorXd& u) override {
    if (!windowed()) return x_.set_data(u);
    x_window_.set_data(u);
    x_waveform_->set_samples(as_samples(u, x_.size(), s_substeps()));
    x_.set_data(u.tail(x_.size()));  // the window's end
  }

  Eigen::VectorXd evaluate(const Eigen::VectorXd& x, int iteration) override {
    if (windowed()) return evaluate_window(x, iteration);
    x_.set_data(x);
    const Interface& y = timed_solve(0, x_);
    check_finite(y, *solvers_[0], iteration);
    y_.set_data(loads_update_ ? loads_update_(x, y.data()) : y.data());
    const Interface& xt = timed_solve(1, y_);
    check_finite(xt, *solvers_[1], iteration);
    return xt.data();
  }

 protected:
  Eigen::Index displacement_size() const override {
    return windowed() ? x_window_.size() : x_.size();
  }

  void on_started() override {
    if (!windowed()) return;
    x_window_ = repeated(x_, s_substeps());
    x_waveform_ = std::make_unique<Waveform>(x_.size(), s_substeps(), interpolation_);
    y_waveform_ = std::make_unique<Waveform>(y_.size(), f_substeps(), interpolation_);
    x_waveform_->reset(x_.data());  // S's initial state, held before the run
    y_waveform_->reset(y_.data());  // F's
    x_window_.set_data(x_waveform_->samples().reshaped());
  }

  void on_step_begun() override {
    if (!windowed()) return;
    x_waveform_->begin_window();  // the unknown's samples are the last window's solution
    y_waveform_->begin_window();
  }

 private:
  bool windowed() const { return f_substeps() > 1 || s_substeps() > 1; }
  int f_substeps() const { return solvers_[0]->substeps(); }
  int s_substeps() const { return solvers_[1]->substeps(); }

  static Eigen::MatrixXd as_samples(const Eigen::VectorXd& u, Eigen::Index size, int samples) {
    return u.reshaped(size, samples);
  }

  /// x~ over the window for x over the window: F's substeps take x at their ends, S's take
  /// F's loads at theirs.
  Eigen::VectorXd evaluate_window(const Eigen::VectorXd& x, int iteration) {
    set_unknown(x);
    Eigen::MatrixXd loads;
    const Eigen::MatrixXd displacement = x_waveform_->at(f_substeps());
    timed(0, [&] { loads = solvers_[0]->solve_substeps(displacement); });
    check_finite_columns(loads, y_, *solvers_[0], iteration);
    y_waveform_->set_samples(loads);
    y_.set_data(loads.col(loads.cols() - 1));
    Eigen::MatrixXd moved;
    // A structure with fewer substeps than the flow takes the loads' mean over each of its
    // steps (time_average): the impulse the flow passed on. The flow takes the displacement
    // at its steps' ends: the volume the wall swept.
    const Eigen::MatrixXd s_loads = time_average_ && s_substeps() < f_substeps()
                                        ? y_waveform_->mean(s_substeps())
                                        : y_waveform_->at(s_substeps());
    timed(1, [&] { moved = solvers_[1]->solve_substeps(s_loads); });
    Interface layout = x_;
    check_finite_columns(moved, layout, *solvers_[1], iteration);
    return moved.reshaped();
  }

  void check_finite_columns(const Eigen::MatrixXd& values, Interface layout,
                            const SolverWrapper& solver, int iteration) const {
    if (values.allFinite()) return;
    for (Eigen::Index j = 0; j < values.cols(); ++j) {
      layout.set_data(values.col(j));
      check_finite(layout, solver, iteration);
    }
  }

  Interface x_window_;  ///< the unknown's layout: x at each of S's substeps
  std::unique_ptr<Waveform> x_waveform_, y_waveform_;
};

}  // namespace

COCOPP_REGISTER(CouplingSchemeRegistry, "serial", SerialScheme)

}  // namespace cocopp
