// aitken: relaxation with a dynamic factor from the last two residuals.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "coupler/coupled_solvers/coupled_solver.hpp"

namespace cocopp {
namespace {

class Aitken : public CoupledSolver {
 public:
  explicit Aitken(const Settings& s)
      : CoupledSolver(s), omega_max_(s.get_in_range("omega_max", 0.5, {0.0, 2.0, true})) {}

 protected:
  /// The first factor of a step continues from the last one of the previous step, capped.
  void on_step_start() override {
    omega_ = std::copysign(std::min(std::abs(omega_), omega_max_), omega_);
    has_previous_ = false;
  }

  Eigen::VectorXd next_input(const Eigen::VectorXd& x, const Eigen::VectorXd&,
                             const Eigen::VectorXd& r) override {
    if (has_previous_) {
      const Eigen::VectorXd dr = r - r_previous_;
      const double dr2 = dr.squaredNorm();
      // A repeated residual gives no new information: keep the factor.
      if (dr2 > 0.0) omega_ = -omega_ * r_previous_.dot(dr) / dr2;
    }
    r_previous_ = r;
    has_previous_ = true;
    return x + omega_ * r;
  }

  void save_own_state(State& state) const override { state.set("omega", omega_); }
  void load_own_state(const State& state) override { omega_ = state.scalar("omega"); }

  std::string describe_settings() const override {
    return fmt::format("omega_max {:g}", omega_max_);
  }

 private:
  double omega_max_;
  double omega_ = omega_max_;
  Eigen::VectorXd r_previous_;
  bool has_previous_ = false;
};

}  // namespace

COCOPP_REGISTER(CoupledSolverRegistry, "aitken", Aitken)

}  // namespace cocopp
