// `gauss_seidel`: block Gauss-Seidel (Dirichlet-Neumann) iterations, x^(k+1) = x~^k, without
// memory or relaxation.
#include "coupler/coupled_solvers/coupled_solver.hpp"

namespace cocopp {
namespace {

class GaussSeidel : public CoupledSolver {
 public:
  using CoupledSolver::CoupledSolver;

 protected:
  Eigen::VectorXd next_input(const Eigen::VectorXd&, const Eigen::VectorXd& xt,
                             const Eigen::VectorXd&) override {
    return xt;
  }
};

}  // namespace

COCOPP_REGISTER(CoupledSolverRegistry, "gauss_seidel", GaussSeidel)

}  // namespace cocopp
