// explicit, gauss_seidel and relaxation: the fixed-point iterations without memory.
#include <fmt/format.h>

#include "coupler/coupled_solvers/coupled_solver.hpp"

namespace cocopp {
namespace {

/// One pass per time step: the structure's answer is accepted without iterating.
class Explicit : public CoupledSolver {
 public:
  using CoupledSolver::CoupledSolver;

 protected:
  bool iterates() const override { return false; }
  Eigen::VectorXd next_input(const Eigen::VectorXd&, const Eigen::VectorXd& xt,
                             const Eigen::VectorXd&) override {
    return xt;
  }
};

/// Block Gauss-Seidel (Dirichlet-Neumann): x^(k+1) = x~^k.
class GaussSeidel : public CoupledSolver {
 public:
  using CoupledSolver::CoupledSolver;

 protected:
  Eigen::VectorXd next_input(const Eigen::VectorXd&, const Eigen::VectorXd& xt,
                             const Eigen::VectorXd&) override {
    return xt;
  }
};

/// Constant under-relaxation: x^(k+1) = x^k + omega r^k.
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

COCOPP_REGISTER(CoupledSolverRegistry, "explicit", Explicit)
COCOPP_REGISTER(CoupledSolverRegistry, "gauss_seidel", GaussSeidel)
COCOPP_REGISTER(CoupledSolverRegistry, "relaxation", Relaxation)

}  // namespace cocopp
