// `explicit`: one pass per time step; the structure's answer is accepted without iterating.
#include "coupler/coupled_solvers/coupled_solver.hpp"

namespace cocopp {
namespace {

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

}  // namespace

COCOPP_REGISTER(CoupledSolverRegistry, "explicit", Explicit)

}  // namespace cocopp
