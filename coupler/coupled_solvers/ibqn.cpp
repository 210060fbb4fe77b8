// ibqn: interface block quasi-Newton (Vierendeels et al. 2007), with one secant model per
// solver, in the Gauss-Seidel order of CoupledSolver.
//
// Formulation. The unknowns are the displacement x and the loads y; the coupled problem is
// x = S(y), y = F(x). Newton's method on the block residual [S(y) - x; F(x) - y] solves
//     [ I    -S' ] [dx]   [ x~ - x ]        x~ = S(y), y~ = F(x),
//     [ -F'   I  ] [dy] = [ y~ - y ]        x <- x + dx, y <- y + dy,
// with the Jacobians F' and S' replaced by secant models: model_f is fitted to the pairs
// (x, y~) and predicts F' dx, model_s to the pairs (y, x~) and predicts S' dy (the `ls` model:
// W c with V c ~ the given difference, i.e. the least-squares Jacobian on the span of the
// secant differences). Eliminating dy gives the Schur complement on x, CoCoNuT's x-update:
//     (I - S'F') dx = (x~ - x) + S' (y~ - y).
// CoupledSolver evaluates F and then S on its output, so the y given to S is y~ = F(x) itself:
// the second right-hand side vanishes, dy = F' dx, and each iteration solves
//     (I - S'F') dx = r,    r = x~ - x,
// matrix-free with GMRES (the operator is I minus a product of low-rank models, so GMRES
// needs at most rank + 1 iterations). The new y is then F(x + dx), evaluated exactly rather
// than predicted as y + dy. CoCoNuT also makes a block update of y before S, which needs a way
// to change the y passed to S; in the order used here that half step is the exact F.
//
// Until both models hold secant information (the first iteration of a run, or of every step
// without reuse), x <- x + omega r, as in iqni.
#include <fmt/format.h>

#include "coupler/coupled_solvers/coupled_solver.hpp"
#include "coupler/coupled_solvers/gmres.hpp"
#include "coupler/coupled_solvers/models/model.hpp"
#include "coupler/coupled_solvers/scaling.hpp"

namespace cocopp {
namespace {

/// A secant model with its type, for describe().
struct NamedModel {
  NamedModel(const Settings& settings, const std::string& key)
      : type(settings.child(key).required<std::string>("type")),
        model(ModelRegistry::instance().create(settings.child(key))) {}

  bool has_information() const { return model->is_ready() && model->columns() > 0; }

  std::string type;
  std::unique_ptr<Model> model;
};

class Ibqn : public CoupledSolver {
 public:
  explicit Ibqn(const Settings& s)
      : CoupledSolver(s),
        omega_(s.get_in_range("omega", 0.01, {0.0, 2.0, true})),
        tolerance_(s.child_or_empty("gmres").get_in_range("tolerance", 1e-8, Range::positive())),
        maximum_iterations_(
            s.child_or_empty("gmres").get_int_in_range("maximum_iterations", 100, 1)),
        f_(s, "model_f"),
        s_(s, "model_s"),
        scaling_(s) {}

 protected:
  void on_initialized() override { scaling_.bind({&x(), &y()}); }
  void on_step_start() override {
    f_.model->initialize_step();
    s_.model->initialize_step();
  }
  void on_step_end() override {
    f_.model->finalize_step();
    s_.model->finalize_step();
  }

  void on_converged(const Eigen::VectorXd& x, const Eigen::VectorXd& xt,
                    const Eigen::VectorXd&) override {
    add_to_models(x, xt);
  }

  Eigen::VectorXd next_input(const Eigen::VectorXd& x, const Eigen::VectorXd& xt,
                             const Eigen::VectorXd& r) override {
    add_to_models(x, xt);
    // Filtering may leave a model without columns: then relax as in the first iteration.
    if (!f_.has_information() || !s_.has_information()) return x + omega_ * r;
    return x + block_update(r);
  }

  std::vector<std::string> take_notes() override {
    std::vector<std::string> notes;
    const std::pair<const NamedModel*, const char*> models[] = {{&f_, "model_f"}, {&s_, "model_s"}};
    for (const auto& [named, key] : models)
      for (const auto& note : named->model->take_notes())
        notes.push_back(std::string(key) + " " + named->type + ": " + note);
    return notes;
  }

  void save_own_state(State& state) const override {
    f_.model->save_state(state.group("model_f"));
    s_.model->save_state(state.group("model_s"));
    scaling_.save_state(state.group("scaling"));
  }
  void load_own_state(const State& state) override {
    f_.model->load_state(state.group("model_f"));
    s_.model->load_state(state.group("model_s"));
    scaling_.load_state(state.group("scaling"));
  }

  std::string describe_settings() const override {
    const std::string scaling = scaling_.enabled() ? ", scaling " + scaling_.describe() : "";
    return fmt::format("omega {:g}, model_f {}, model_s {}{}", omega_, f_.type, s_.type, scaling);
  }

 private:
  void add_to_models(const Eigen::VectorXd& x, const Eigen::VectorXd& xt) {
    // y() holds F(x) of this iteration: the base class stores it before calling S.
    const Eigen::VectorXd& y = this->y().data();
    f_.model->add(scaling_.apply(kX, x), y);
    s_.model->add(scaling_.apply(kY, y), xt);
  }

  /// dx with (I - S'F') dx = r. A GMRES that stops at maximum_iterations still returns the
  /// best dx of its Krylov space; the coupling iteration corrects what remains.
  Eigen::VectorXd block_update(const Eigen::VectorXd& r) {
    auto apply = [this](const Eigen::VectorXd& dx) -> Eigen::VectorXd {
      const Eigen::VectorXd dy = f_.model->predict(scaling_.apply(kX, dx));
      return dx - s_.model->predict(scaling_.apply(kY, dy));
    };
    return gmres(apply, r, tolerance_, maximum_iterations_).x;
  }

  double omega_;
  double tolerance_;
  int maximum_iterations_;
  NamedModel f_;
  NamedModel s_;
  VariableScaling scaling_;  ///< weights of the models' inputs: x (kX) and y (kY)
  static constexpr std::size_t kX = 0, kY = 1;
};

}  // namespace

COCOPP_REGISTER(CoupledSolverRegistry, "ibqn", Ibqn)

}  // namespace cocopp
