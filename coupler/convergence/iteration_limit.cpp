// iteration_limit: stop after a number of coupling iterations (accepting the step unconverged).
#include <fmt/format.h>

#include "coupler/convergence/convergence_criterion.hpp"

namespace cocopp {
namespace {

class IterationLimit : public ConvergenceCriterion {
 public:
  explicit IterationLimit(const Settings& s) : maximum_(s.get_int_in_range("maximum", 15, 1)) {}
  void initialize_step() override { iterations_ = 0; }
  void update(const Eigen::VectorXd&) override { ++iterations_; }
  bool is_satisfied() const override { return iterations_ >= maximum_; }
  bool tolerance_met() const override { return false; }
  bool limit_reached() const override { return is_satisfied(); }
  std::string describe() const override { return fmt::format("iteration_limit {}", maximum_); }

 private:
  int maximum_;
  int iterations_ = 0;
};

}  // namespace

COCOPP_REGISTER(ConvergenceCriterionRegistry, "iteration_limit", IterationLimit)

}  // namespace cocopp
