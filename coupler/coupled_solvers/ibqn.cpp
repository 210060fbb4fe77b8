// ibqn: interface block quasi-Newton (Vierendeels et al. 2007), with one secant model per
// solver, as CoCoNuT's ibqn.
//
// Formulation. The unknowns are the displacement x and the loads y; the coupled problem is
// x = S(y), y = F(x). Newton's method on the block residual [S(y) - x; F(x) - y], with the
// Jacobians F' and S' replaced by secant models (model_f fitted to the pairs (x, y~ = F(x)),
// model_s to the pairs (y, x~ = S(y)); the `ls` model gives W c with V c ~ the difference,
// the least-squares Jacobian on the span of the secant differences), is solved block by block,
// each block with the other's newest data:
//     (I - S'F') dx = (x~ - x) + S' (y~ - y),   x <- x + dx,  then y~ = F(x);
//     (I - F'S') dy = (y~ - y) + F' (x~ - x),   y <- y + dy,  then x~ = S(y).
// The second solve (second_solver_input) uses the x just updated and the x~ of the previous
// iteration, so S gets loads that already account for the displacement update, not F(x)
// itself. Both are solved matrix-free with GMRES: the operators are I minus a product of
// low-rank models, so GMRES needs at most rank + 1 iterations.
//
// Until both models hold secant information (the first iterations of a run, or of every step
// without reuse), x <- x + omega r and S gets y~ = F(x), as in iqni; so does the first
// iteration of every step, whose x comes from the predictor.
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
    first_iteration_ = true;
  }
  void on_step_end() override {
    f_.model->finalize_step();
    s_.model->finalize_step();
  }

  Eigen::VectorXd second_solver_input(const Eigen::VectorXd& x,
                                      const Eigen::VectorXd& yt) override {
    f_.model->add(scaling_.apply(kX, x), yt);
    yt_ = yt;
    if (first_iteration_ || !both_have_information())
      y_ = yt;
    else
      y_ = y_previous_ +
           solve_block(&Ibqn::identity_minus_fs, (yt - y_previous_) + predict_f(xt_previous_ - x));
    return y_;
  }

  void on_converged(const Eigen::VectorXd&, const Eigen::VectorXd& xt,
                    const Eigen::VectorXd&) override {
    s_.model->add(scaling_.apply(kY, y_), xt);
  }

  Eigen::VectorXd next_input(const Eigen::VectorXd& x, const Eigen::VectorXd& xt,
                             const Eigen::VectorXd& r) override {
    s_.model->add(scaling_.apply(kY, y_), xt);
    first_iteration_ = false;
    y_previous_ = y_;
    xt_previous_ = xt;
    // Filtering may leave a model without columns: then relax as in the first iteration.
    if (!both_have_information()) return x + omega_ * r;
    return x + solve_block(&Ibqn::identity_minus_sf, r + predict_s(yt_ - y_));
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
  bool both_have_information() const { return f_.has_information() && s_.has_information(); }

  /// F' dx and S' dy from the secant models (their inputs weighted as they were fitted).
  Eigen::VectorXd predict_f(const Eigen::VectorXd& dx) {
    return f_.model->predict(scaling_.apply(kX, dx));
  }
  Eigen::VectorXd predict_s(const Eigen::VectorXd& dy) {
    return s_.model->predict(scaling_.apply(kY, dy));
  }
  /// The block operators I - S'F' (on dx) and I - F'S' (on dy).
  Eigen::VectorXd identity_minus_sf(const Eigen::VectorXd& dx) {
    return dx - predict_s(predict_f(dx));
  }
  Eigen::VectorXd identity_minus_fs(const Eigen::VectorXd& dy) {
    return dy - predict_f(predict_s(dy));
  }

  /// The solution of operator(d) = b. A GMRES that stops at maximum_iterations still returns
  /// the best d of its Krylov space; the coupling iteration corrects what remains.
  using BlockOperator = Eigen::VectorXd (Ibqn::*)(const Eigen::VectorXd&);
  Eigen::VectorXd solve_block(BlockOperator block, const Eigen::VectorXd& b) {
    auto apply = [this, block](const Eigen::VectorXd& d) { return (this->*block)(d); };
    return gmres(apply, b, tolerance_, maximum_iterations_).x;
  }

  double omega_;
  double tolerance_;
  int maximum_iterations_;
  NamedModel f_;
  NamedModel s_;
  VariableScaling scaling_;  ///< weights of the models' inputs: x (kX) and y (kY)
  static constexpr std::size_t kX = 0, kY = 1;

  bool first_iteration_ = true;  ///< of the step: S gets y~ = F(x)
  Eigen::VectorXd y_;            ///< the loads given to S in this iteration
  Eigen::VectorXd yt_;           ///< F(x) of this iteration
  Eigen::VectorXd y_previous_;   ///< the loads given to S in the previous iteration
  Eigen::VectorXd xt_previous_;  ///< S's output of the previous iteration
};

}  // namespace

COCOPP_REGISTER(CoupledSolverRegistry, "ibqn", Ibqn)

}  // namespace cocopp
