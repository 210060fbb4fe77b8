// iqnism: interface quasi-Newton with a surrogate (IQN-ILSM; Delaissé et al., surrogate-based
// acceleration of quasi-Newton techniques for FSI, Computers & Structures 2022; CoCoNuT's
// `iqnism`).
//
// IQN-ILS learns the inverse Jacobian of the residual only on the span of its secant columns;
// what they do not explain gets a Gauss-Seidel step, which a strongly coupled problem amplifies.
// A surrogate, a cheaper model of the same coupled problem (coarser or simpler solvers), is
// solved first in every time step by its own coupled solver (iqni), whose secant model then
// approximates the surrogate's inverse Jacobian. With dr = -r and the model's fit V c ~ dr:
//     x <- x~ + W c + N_s (dr - V c)          (the model holds information)
//     x <- x~ + N_s dr + (1 - omega) q_s      (it does not yet: the step's first update)
//     x <- x + omega r                        (neither does the surrogate)
// where N_s is the surrogate's secant model and q_s = dr - V_s c_s the part of dr its columns
// do not explain, which is relaxed by omega. Where the surrogate's Jacobian is exact, the
// quasi-Newton step is Newton's; where it is poor, the model's own columns take over.
//
// After the step has converged the surrogate's solvers are run once more with the step's
// solution (`surrogate.synchronize`), so that the surrogate starts the next step from the
// real state, not from its own. The surrogate's solution can also give the step's first x
// (`surrogate.prediction`: its change over the step added to the last solution, or its value).
//
// The surrogate's interface is the case's (the same model parts, points and variables), or
// `surrogate.mapper` (an interpolator with transformers, as a mapped solver's; or one mapper
// each way) maps between the two, block by block: a surrogate on a coarser mesh, or a 1D
// model standing in for a 3D one.
#include <fmt/format.h>

#include "coupler/coupled_solvers/coupled_solver.hpp"
#include "coupler/coupled_solvers/models/model.hpp"
#include "coupler/coupled_solvers/surrogate_mapping.hpp"

namespace cocopp {
namespace {

class Iqnism : public CoupledSolver {
 public:
  explicit Iqnism(const Settings& s)
      : CoupledSolver(s),
        omega_(s.get_in_range("omega", 0.01, {0.0, 2.0, true})),
        model_type_(s.child("model").required<std::string>("type")),
        model_(ModelRegistry::instance().create(s.child("model"))),
        surrogate_settings_(s.child("surrogate")),
        prediction_(
            surrogate_settings_.get_choice("prediction", "none", {"none", "change", "value"})),
        synchronize_(surrogate_settings_.get<bool>("synchronize", true)),
        mapping_(surrogate_settings_) {
    if (!model_->fits_residuals())
      s.child("model").fail("type",
                            "iqnism needs a model that fits residuals ('ls'): the "
                            "surrogate acts on the part of the residual that the "
                            "model's columns do not explain, got '" +
                                model_type_ + "'");
    require_serial_scheme(s, "its surrogate models the serial fixed point x = S(F(x))");
  }

  bool takes_substeps() const override { return false; }

  void create_own_solvers(const RunSettings& run) override {
    const Settings coupled = surrogate_settings_.child("coupled_solver");
    surrogate_ = CoupledSolverRegistry::instance().create(coupled);
    surrogate_->create_own_solvers(run);
    if (surrogate_->residual_model() == nullptr)
      coupled.fail("type",
                   "the surrogate's coupled solver must be 'iqni' without scaling: its secant "
                   "model is the surrogate's Jacobian");
    const auto wrappers = surrogate_settings_.list("solver_wrappers");
    if (wrappers.size() != 2)
      surrogate_settings_.fail("solver_wrappers",
                               "needs exactly two solver wrappers, as the case's own, got " +
                                   std::to_string(wrappers.size()));
    for (const auto& w : wrappers)
      surrogate_solvers_.push_back(SolverWrapperRegistry::instance().create(w, run));
  }

  void finalize() override {
    for (auto& solver : surrogate_solvers_) solver->finalize();
  }

  void save_own_solver_restarts(int step) override {
    const OwnSolversStopwatch stopwatch(*this);
    surrogate_->save_solver_restarts(step);
  }

 protected:
  void on_initialized() override {
    if (!surrogate_) throw std::logic_error("iqnism: create_own_solvers() was not called");
    surrogate_->initialize(*surrogate_solvers_[0], *surrogate_solvers_[1]);
    mapping_.initialize(x(), surrogate_->x());
    last_surrogate_solution_ = mapping_.from_surrogate(surrogate_->x().data());
  }

  void on_step_start() override {
    model_->initialize_step();
    const OwnSolversStopwatch stopwatch(*this);
    StepRecord record;
    try {
      record = surrogate_->iterate_step(current_step(), current_time());
    } catch (const DivergenceError& e) {
      // Say whose coupling it was: the message alone reads like the case's own.
      throw DivergenceError(e.kind, e.step, e.iteration,
                            std::string("iqnism's surrogate: ") + e.what() +
                                " (the surrogate's coupled_solver is set under "
                                "coupled_solver.surrogate)");
    }
    set_own_iterations(record.iterations);
    if (!record.converged)
      notes_.push_back(fmt::format("the surrogate stopped at its iteration limit ({} iterations)",
                                   record.iterations));
    pending_surrogate_record_ = std::move(record);
  }

  Eigen::VectorXd first_input(const Eigen::VectorXd& predicted) override {
    const Eigen::VectorXd solution = mapping_.from_surrogate(surrogate_->x().data());
    Eigen::VectorXd first = predicted;
    if (prediction_ == "value") first = solution;
    if (prediction_ == "change") first = x().data() + (solution - last_surrogate_solution_);
    last_surrogate_solution_ = solution;
    return first;
  }

  Eigen::VectorXd next_input(const Eigen::VectorXd& x, const Eigen::VectorXd& xt,
                             const Eigen::VectorXd& r) override {
    model_->add(r, xt);
    const Eigen::VectorXd dr = -r;
    const bool surrogate_ready = surrogate_model().is_ready() && surrogate_model().columns() > 0;
    if (model_->is_ready() && model_->columns() > 0) {
      Eigen::VectorXd dxt = model_->predict(dr);
      if (surrogate_ready) dxt += surrogate_predict(dr - model_->fitted(dr));
      return xt + dxt;
    }
    if (!surrogate_ready) return x + omega_ * r;
    // x~ steps the unexplained part r_u of r fully; omega relaxes it: x~ - (1 - omega) r_u,
    // and q_s = -r_u.
    return xt + surrogate_predict(dr) + (1.0 - omega_) * surrogate_unexplained(dr);
  }

  void on_converged(const Eigen::VectorXd&, const Eigen::VectorXd& xt,
                    const Eigen::VectorXd& r) override {
    model_->add(r, xt);
  }

  void on_step_end() override {
    model_->finalize_step();
    const OwnSolversStopwatch stopwatch(*this);
    if (synchronize_) surrogate_->synchronize(mapping_.to_surrogate(x().data()));
    surrogate_->commit_step(pending_surrogate_record_);
  }

  Model& surrogate_model() { return *surrogate_->residual_model(); }
  /// N_s dr: the surrogate's model's dx~, in the case's interface.
  Eigen::VectorXd surrogate_predict(const Eigen::VectorXd& dr) {
    return mapping_.from_surrogate(surrogate_model().predict(mapping_.to_surrogate(dr)));
  }
  /// q_s: the part of dr the surrogate's columns do not explain (none for a Jacobian model).
  Eigen::VectorXd surrogate_unexplained(const Eigen::VectorXd& dr) {
    if (!surrogate_model().fits_residuals()) return Eigen::VectorXd::Zero(dr.size());
    const Eigen::VectorXd on_surrogate = mapping_.to_surrogate(dr);
    return mapping_.from_surrogate(on_surrogate - surrogate_model().fitted(on_surrogate));
  }

  std::vector<std::string> take_notes() override {
    std::vector<std::string> notes = model_->take_notes();
    for (auto& note : notes) note = "model " + model_type_ + ": " + note;
    for (auto& note : notes_) notes.push_back(std::move(note));
    notes_.clear();
    return notes;
  }

  void save_own_state(State& state) const override {
    model_->save_state(state.group("model"));
    surrogate_->save_state(state.group("surrogate"));
    state.group("surrogate_prediction")
        .set("last_solution", Eigen::MatrixXd(last_surrogate_solution_));
  }
  void load_own_state(const State& state) override {
    model_->load_state(state.group("model"));
    surrogate_->load_state(state.group("surrogate"));
    last_surrogate_solution_ = state.group("surrogate_prediction").matrix("last_solution").col(0);
  }

  std::string divergence_advice() const override { return quasi_newton_advice(omega_); }

  std::string describe_settings() const override {
    std::string solvers;
    for (const auto& solver : surrogate_solvers_)
      solvers += (solvers.empty() ? "" : " + ") + solver->name();
    return fmt::format("omega {:g}, model {}, surrogate {} on {}{}{}", omega_, model_type_,
                       surrogate_ ? surrogate_->describe() : "?", solvers,
                       synchronize_ ? ", synchronized" : "",
                       prediction_ == "none" ? "" : ", prediction from its " + prediction_);
  }

 private:
  double omega_;
  std::string model_type_;
  std::unique_ptr<Model> model_;
  Settings surrogate_settings_;
  std::string prediction_;  ///< none | change | value
  bool synchronize_;
  SurrogateMapping mapping_;
  std::unique_ptr<CoupledSolver> surrogate_;
  std::vector<std::unique_ptr<SolverWrapper>> surrogate_solvers_;
  StepRecord pending_surrogate_record_;      ///< the surrogate's step, committed with ours
  Eigen::VectorXd last_surrogate_solution_;  ///< for prediction "change"
  std::vector<std::string> notes_;
};

}  // namespace

COCOPP_REGISTER(CoupledSolverRegistry, "iqnism", Iqnism)

}  // namespace cocopp
