// `solver_coupling_convergence` (CoCoNuT's criterion of that name): met when one solver's own
// iterations (Newton, PIMPLE's outer loop) converged at their first iteration in the last
// coupling iteration: the new input no longer changes that solver's solution beyond its own
// tolerance. With both solvers so (`and` of two of them), more coupling iterations would only
// repeat the solvers' answers: the step stops without a residual tolerance to tune. The solver
// is asked to report it once both have started (SolverWrapper::start_reporting_convergence);
// one that cannot tell stops the run with its reason.
#include <fmt/format.h>

#include "coupler/convergence/convergence_criterion.hpp"
#include "solver_wrappers/solver_wrapper.hpp"

namespace cocopp {
namespace {

class SolverCouplingConvergence : public ConvergenceCriterion {
 public:
  explicit SolverCouplingConvergence(const Settings& s)
      : index_(s.required_int_in_range("solver_index", 0, 1)) {}
  void attach_solvers(const std::array<SolverWrapper*, 2>& solvers) override {
    solver_ = solvers[static_cast<std::size_t>(index_)];
    solver_->start_reporting_convergence();
  }
  void initialize_step() override { met_ = false; }
  void update(const Eigen::VectorXd&) override {
    met_ = solver_ != nullptr && solver_->converged_at_first_iteration();
  }
  bool is_satisfied() const override { return met_; }
  std::string progress() const override {
    return fmt::format("{} {}", solver_name(), met_ ? "converged" : "iterating");
  }
  std::string describe() const override {
    return fmt::format("solver_coupling_convergence({})", solver_name());
  }

 private:
  std::string solver_name() const {
    return solver_ != nullptr ? solver_->name() : fmt::format("solver_index {}", index_);
  }

  int index_;
  SolverWrapper* solver_ = nullptr;
  bool met_ = false;
};

}  // namespace

COCOPP_REGISTER(ConvergenceCriterionRegistry, "solver_coupling_convergence",
                SolverCouplingConvergence)

}  // namespace cocopp
