// `relaxation`: constant under-relaxation, x^(k+1) = x^k + omega r^k.
#include <fmt/format.h>

#include "coupler/coupled_solvers/coupled_solver.hpp"

namespace cocopp {
namespace {

class Relaxation : public CoupledSolver {
 public:
  explicit Relaxation(const Settings& s)
      : CoupledSolver(s), omega_(s.required_in_range("omega", {0.0, 2.0, true})) {}

 protected:
  Eigen::VectorXd next_input(const Eigen::VectorXd& x, const Eigen::VectorXd&,
                             const Eigen::VectorXd& r) override {
    return x + omega_ * r;
  }
  std::string describe_settings() const override { return fmt::format("omega {:g}", omega_); }

 private:
  double omega_;
};

}  // namespace

COCOPP_REGISTER(CoupledSolverRegistry, "relaxation", Relaxation)

}  // namespace cocopp
