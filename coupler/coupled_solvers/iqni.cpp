// iqni: interface quasi-Newton with an approximation of the inverse Jacobian (IQN-I), the
// Jacobian model chosen by `model` (ls = IQN-ILS). x^(k+1) = x~^k + W c, where the model fits
// V c ~ -r^k; relaxation with omega until the model has information. With `scheme: parallel`
// x is the stacked unknown (x, y) and the fit weighs each field (`scaling`, residual_sum
// unless set): unweighted, a pressure's residual in Pa would drown the displacement's in m.
//
// `mixing` (beta, model ls only) is Anderson acceleration's mixing parameter (Walker and Ni,
// 2011): x^(k+1) = x~^k + W c - (1 - beta) (r^k + V c). IQN-ILS is beta = 1: the part of the
// residual the secant columns do not explain, r^k + V c, gets a Gauss-Seidel step. Where
// Gauss-Seidel amplifies errors a hundredfold (a wire yielding under a stiff film), that step
// throws the iterate far off; beta relaxes it, as omega relaxes the first step.
#include <fmt/format.h>

#include "coupler/coupled_solvers/coupled_solver.hpp"
#include "coupler/coupled_solvers/models/model.hpp"
#include "coupler/coupled_solvers/scaling.hpp"

namespace cocopp {
namespace {

class Iqni : public CoupledSolver {
 public:
  explicit Iqni(const Settings& s)
      : CoupledSolver(s),
        omega_(s.get_in_range("omega", 0.01, {0.0, 2.0, true})),
        mixing_(s.get_in_range("mixing", 1.0, {0.0, 1.0, true})),
        model_type_(s.child("model").required<std::string>("type")),
        model_(ModelRegistry::instance().create(s.child("model"))),
        scaling_(s, side_by_side()) {
    if (mixing_ != 1.0 && !model_->fits_residuals())
      s.fail("mixing", "is defined for model 'ls' only (model '" + model_type_ +
                           "' approximates a Jacobian, not a least-squares fit of residuals)");
  }

 public:
  // With scaling, the model works in weighted units: no use to another coupled solver.
  Model* residual_model() override { return scaling_.enabled() ? nullptr : model_.get(); }

 protected:
  void on_initialized() override { scaling_.bind(unknown_layouts()); }
  void on_step_start() override {
    model_->initialize_step();
    if (scaling_.changing()) rescale_model();
  }
  void on_step_end() override {
    model_->finalize_step();
    first_step_ = false;
  }

  void on_converged(const Eigen::VectorXd&, const Eigen::VectorXd& xt,
                    const Eigen::VectorXd& r) override {
    model_->add(weigh(r), xt);
  }

  Eigen::VectorXd next_input(const Eigen::VectorXd& x, const Eigen::VectorXd& xt,
                             const Eigen::VectorXd& r) override {
    const Eigen::VectorXd weighted_r = weigh(r);
    model_->add(weighted_r, xt);
    if (model_->is_ready()) {
      const Eigen::VectorXd dxt = model_->predict(-weighted_r);
      // Filtering may have removed every column: then relax as in the first iteration.
      if (model_->columns() > 0) {
        if (mixing_ == 1.0) return xt + dxt;
        const Eigen::VectorXd unexplained =
            scaling_.remove_all(weighted_r + model_->fitted(-weighted_r));
        return xt + dxt - (1.0 - mixing_) * unexplained;
      }
    }
    return x + omega_ * r;
  }

  /// r in the model's weights. residual_sum takes r into its sums; its weights follow at the
  /// next step's start, and in the first step (no weights yet) at once.
  Eigen::VectorXd weigh(const Eigen::VectorXd& r) {
    if (scaling_.changing()) {
      scaling_.accumulate(r);
      if (first_step_) rescale_model();
    }
    return scaling_.apply_all(r);
  }

  void rescale_model() {
    const Eigen::VectorXd factors = scaling_.refresh();
    if (factors.size() > 0) model_->rescale(factors);
  }

  std::vector<std::string> take_notes() override {
    std::vector<std::string> notes = model_->take_notes();
    for (auto& note : notes) note = "model " + model_type_ + ": " + note;
    return notes;
  }

  void save_own_state(State& state) const override {
    model_->save_state(state.group("model"));
    scaling_.save_state(state.group("scaling"));
  }
  void load_own_state(const State& state) override {
    model_->load_state(state.group("model"));
    scaling_.load_state(state.group("scaling"));
  }

  std::string divergence_advice() const override { return quasi_newton_advice(omega_); }

  std::string describe_settings() const override {
    const std::string scaling = scaling_.enabled() ? ", scaling " + scaling_.describe() : "";
    const std::string mixing = mixing_ == 1.0 ? "" : fmt::format(", mixing {:g}", mixing_);
    return fmt::format("omega {:g}{}, model {}{}", omega_, mixing, model_type_, scaling);
  }

 private:
  double omega_;
  double mixing_;  ///< Anderson's beta: 1 is IQN-ILS
  std::string model_type_;
  std::unique_ptr<Model> model_;
  VariableScaling scaling_;
  bool first_step_ = true;  ///< of this run (also a restarted one)
};

}  // namespace

COCOPP_REGISTER(CoupledSolverRegistry, "iqni", Iqni)

}  // namespace cocopp
