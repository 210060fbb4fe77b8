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
// itself.
//
// Solving the blocks. With two `ls` models each Jacobian is of low rank: F' = W_f R_f⁻¹ Q_fᵀ D_x
// (V_f = Q_f R_f, inputs weighted by D_x as fitted) and the same for S'. So a block operator
// is the identity minus a low-rank product, which the Sherman-Morrison-Woodbury identity
// inverts in the small space of the columns (solve_block). What that needs of the interface,
// Q_sᵀ D_y W_f and Q_fᵀ D_x W_s, is kept up to date column by column (CrossProjection), so an
// iteration costs O(n k) where GMRES, with one pass over both models per Krylov iteration and
// about k of those, costs O(n k²). Any other model, and a singular block, is solved
// matrix-free with GMRES (at most rank + 1 iterations).
//
// Convergence. The residual r = x~ - x says that S(y) is close to x; but y is not F(x), so the
// pair the step ends with is off by the loads' mismatch y~ - y as well. CoCoNuT's ibqn, and
// `convergence_residual: block` (the default), measure r alone: at the same tolerance that
// ends a step 20 times further from the solution than IQN-ILS on the tube, 280 times on
// Turek-Hron FSI3 (docs/coupling.md). `convergence_residual: coupled` measures r + S'(y~ - y), the
// estimate by S's secant model of S(F(x)) - x: the residual the other methods measure.
//
// Until both models hold secant information (the first iterations of a run, or of every step
// without reuse), x <- x + omega r and S gets y~ = F(x), as in iqni; so does the first
// iteration of every step, whose x comes from the predictor.
#include <fmt/format.h>

#include <Eigen/LU>

#include "coupler/coupled_solvers/coupled_solver.hpp"
#include "coupler/coupled_solvers/gmres.hpp"
#include "coupler/coupled_solvers/models/cross_projection.hpp"
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
        coupled_residual_(s.get_choice("convergence_residual", "block", {"block", "coupled"}) ==
                          "coupled"),
        f_(s, "model_f"),
        s_(s, "model_s"),
        scaling_(s) {
    require_serial_scheme(s, "its block update gives S loads made from F's answer to this x");
  }

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

  bool takes_substeps() const override { return false; }

  Eigen::VectorXd second_solver_input(const Eigen::VectorXd& x,
                                      const Eigen::VectorXd& yt) override {
    f_.model->add(scaling_.apply(kX, x), yt);
    yt_ = yt;
    if (first_iteration_ || !both_have_information())
      y_ = yt;
    else
      y_ = y_previous_ + solve_y_block((yt - y_previous_) + predict_f(xt_previous_ - x));
    return y_;
  }

  Eigen::VectorXd convergence_residual(const Eigen::VectorXd& r) override {
    if (!coupled_residual_ || !s_.has_information()) return r;
    return r + predict_s(yt_ - y_);
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
    return x + solve_x_block(r + predict_s(yt_ - y_));
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

  std::string divergence_advice() const override { return quasi_newton_advice(omega_); }

  std::string describe_settings() const override {
    const std::string scaling = scaling_.enabled() ? ", scaling " + scaling_.describe() : "";
    const std::string residual = coupled_residual_ ? ", convergence_residual coupled" : "";
    return fmt::format("omega {:g}, model_f {}, model_s {}{}{}", omega_, f_.type, s_.type, scaling,
                       residual);
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

  /// dx with (I - S'F') dx = b, and dy with (I - F'S') dy = b.
  Eigen::VectorXd solve_x_block(const Eigen::VectorXd& b) {
    return solve_block({s_, kY, sf_}, {f_, kX, fs_}, &Ibqn::identity_minus_sf, b);
  }
  Eigen::VectorXd solve_y_block(const Eigen::VectorXd& b) {
    return solve_block({f_, kX, fs_}, {s_, kY, sf_}, &Ibqn::identity_minus_fs, b);
  }

  /// One factor of a block's product: a model, the interface its inputs are weighted as, and
  /// the other model's output columns kept projected onto its fit's basis.
  struct Factor {
    const NamedModel& model;
    std::size_t input;
    CrossProjection& onto_other;
  };

  /// d with (I - O' I') d = b for the `outer` model applied after the `inner` one: exactly by
  /// Woodbury when both are least-squares fits, otherwise (or if the small system is singular)
  /// by GMRES on `block`.
  using BlockOperator = Eigen::VectorXd (Ibqn::*)(const Eigen::VectorXd&);
  Eigen::VectorXd solve_block(Factor outer, Factor inner, BlockOperator block,
                              const Eigen::VectorXd& b) {
    const SecantColumns* o = outer.model.model->least_squares_columns();
    const SecantColumns* i = inner.model.model->least_squares_columns();
    if (o != nullptr && i != nullptr) {
      // In the orthonormal bases of the two fits (V = Q R): with G = Q_oᵀ D_o W_i R_i⁻¹ and
      // H = Q_iᵀ D_i W_o R_o⁻¹, (I - O'I')⁻¹ b = b + W_o R_o⁻¹ (I - G H)⁻¹ G Q_iᵀ D_i b.
      // I - G H is the block operator itself on the span of Q_o, so its conditioning is the
      // operator's, not that of the secant columns.
      const auto times_r_inverse = [](Eigen::MatrixXd m, const SecantColumns& of) {
        of.qr().r().triangularView<Eigen::Upper>().solveInPlace<Eigen::OnTheRight>(m);
        return m;
      };
      const Eigen::MatrixXd g =
          times_r_inverse(outer.onto_other.compute(*o, scaling_.weights(outer.input), *i), *i);
      const Eigen::MatrixXd h =
          times_r_inverse(inner.onto_other.compute(*i, scaling_.weights(inner.input), *o), *o);
      const Eigen::FullPivLU<Eigen::MatrixXd> small(Eigen::MatrixXd::Identity(g.rows(), g.rows()) -
                                                    g * h);
      // A singular block (reused columns that describe another state can make S'F' have an
      // eigenvalue 1 on their span) goes to GMRES, whose minimal residual copes with it; a
      // minimum-norm solution of the small system instead stalled or diverged on the tube.
      if (small.isInvertible()) {
        const Eigen::VectorXd z = o->qr().r().triangularView<Eigen::Upper>().solve(
            small.solve(g * i->qr().project(scaling_.apply(inner.input, b))));
        if (z.allFinite()) return b + o->combine_w(z);
      }
    }
    // A GMRES that stops at maximum_iterations still returns the best d of its Krylov space;
    // the coupling iteration corrects what remains.
    auto apply = [this, block](const Eigen::VectorXd& d) { return (this->*block)(d); };
    return gmres(apply, b, tolerance_, maximum_iterations_).x;
  }

  double omega_;
  double tolerance_;
  int maximum_iterations_;
  bool coupled_residual_;  ///< convergence on r + S'(y~ - y) rather than r
  NamedModel f_;
  NamedModel s_;
  VariableScaling scaling_;  ///< weights of the models' inputs: x (kX) and y (kY)
  CrossProjection sf_;       ///< Q_sᵀ D_y W_f, kept column by column
  CrossProjection fs_;       ///< Q_fᵀ D_x W_s
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
