// aitken: relaxation with a dynamic factor from the last two residuals (Irons and Tuck 1969;
// for FSI, Kuttler and Wall 2008):
//     omega_k = -omega_(k-1) r_(k-1) . (r_k - r_(k-1)) / |r_k - r_(k-1)|^2,   x <- x + omega_k r_k.
// The factor is updated with every new residual, also the one that ends a step, as CoCoNuT
// does; the next step starts from that factor, capped at omega_max. With `scheme: parallel`
// the residual is the stacked (x~ - x, y~ - y), and the factor's dot products weigh each
// field (`scaling`, residual_sum unless set), else the loads' residual alone would set it.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "coupler/coupled_solvers/coupled_solver.hpp"
#include "coupler/coupled_solvers/scaling.hpp"

namespace cocopp {
namespace {

class Aitken : public CoupledSolver {
 public:
  explicit Aitken(const Settings& s)
      : CoupledSolver(s),
        omega_max_(s.get_in_range("omega_max", 0.5, {0.0, 2.0, true})),
        scaling_(s, side_by_side()) {}

 protected:
  void on_initialized() override { scaling_.bind(unknown_layouts()); }

  /// The first factor of a step continues from the last one of the previous step, capped.
  void on_step_start() override {
    omega_ = std::copysign(std::min(std::abs(omega_), omega_max_), omega_);
    has_previous_ = false;
  }

  Eigen::VectorXd next_input(const Eigen::VectorXd& x, const Eigen::VectorXd&,
                             const Eigen::VectorXd& r) override {
    update_factor(r);
    return x + omega_ * r;
  }

  void on_converged(const Eigen::VectorXd&, const Eigen::VectorXd&,
                    const Eigen::VectorXd& r) override {
    update_factor(r);
  }

  void save_own_state(State& state) const override {
    state.set("omega", omega_);
    if (scaling_.enabled()) scaling_.save_state(state.group("scaling"));
  }
  void load_own_state(const State& state) override {
    omega_ = state.scalar("omega");
    if (scaling_.enabled() && state.has_group("scaling"))
      scaling_.load_state(state.group("scaling"));
  }

  std::string divergence_advice() const override {
    return fmt::format(
        "Aitken's factor follows the last two residuals and can overshoot: cap it lower "
        "(omega_max {:g}; try {:g}), or use a quasi-Newton method (coupled_solver type 'iqni' "
        "with model 'ls'), or take a smaller delta_t.",
        omega_max_, omega_max_ / 10);
  }

  std::string describe_settings() const override {
    const std::string scaling = scaling_.enabled() ? ", scaling " + scaling_.describe() : "";
    return fmt::format("omega_max {:g}{}", omega_max_, scaling);
  }

 private:
  void update_factor(const Eigen::VectorXd& r) {
    // Both residuals weighed alike: the previous one is kept unweighted.
    if (scaling_.changing()) {
      scaling_.accumulate(r);
      scaling_.refresh();
    }
    if (has_previous_) {
      const Eigen::VectorXd weighted = scaling_.apply_all(r);
      const Eigen::VectorXd previous = scaling_.apply_all(r_previous_);
      const Eigen::VectorXd dr = weighted - previous;
      const double dr2 = dr.squaredNorm();
      // A repeated residual gives no new information: keep the factor.
      if (dr2 > 0.0) omega_ = -omega_ * previous.dot(dr) / dr2;
    }
    r_previous_ = r;
    has_previous_ = true;
  }

  double omega_max_;
  VariableScaling scaling_;
  double omega_ = omega_max_;
  Eigen::VectorXd r_previous_;
  bool has_previous_ = false;
};

}  // namespace

COCOPP_REGISTER(CoupledSolverRegistry, "aitken", Aitken)

}  // namespace cocopp
