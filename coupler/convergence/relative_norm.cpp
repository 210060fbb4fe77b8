// `relative_norm`: ||r_k|| / ||r_1|| < tolerance, with r_1 the first residual of the time step.
// A first residual of exactly zero means the prediction already solves the step: that counts
// as converged. `reference: largest` divides by the largest residual of the step so far
// instead: with the solvers side by side (scheme parallel) the first displacement residual
// S(y) - x can be near zero while the loads' is not (a step whose loads the predictor misses
// starts with the structure answering the predicted loads with the predicted displacement).
#include <fmt/format.h>

#include "coupler/convergence/norm_criterion.hpp"

namespace cocopp {
namespace {

class RelativeNorm : public NormCriterion {
 public:
  explicit RelativeNorm(const Settings& s)
      : NormCriterion(s, true),
        largest_(s.get_choice("reference", "first", {"first", "largest"}) == "largest") {}
  void initialize_step() override { first_ = last_ = -1.0; }
  void update(const Eigen::VectorXd& r) override {
    last_ = norm(r);
    if (first_ < 0.0 || (largest_ && last_ > first_)) first_ = last_;
  }
  bool is_satisfied() const override {
    if (last_ < 0.0) return false;
    if (first_ == 0.0) return true;
    return last_ / first_ < tolerance_;
  }
  std::string progress() const override {
    if (first_ <= 0.0 || last_ < 0.0) return "";
    return fmt::format("relative{} {:.2e}", order_ == "2" ? "" : "(" + order_ + ")",
                       last_ / first_);
  }
  std::string describe() const override {
    return fmt::format("relative_norm({}{}) < {:g}", order_, largest_ ? ", to the largest" : "",
                       tolerance_);
  }

 private:
  bool largest_;
  double first_ = -1.0;  ///< the reference: the first residual, or the largest so far
  double last_ = -1.0;
};

}  // namespace

COCOPP_REGISTER(ConvergenceCriterionRegistry, "relative_norm", RelativeNorm)

}  // namespace cocopp
