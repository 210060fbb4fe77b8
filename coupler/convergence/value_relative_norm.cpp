// `value_relative_norm`: ||r_k|| / ||x~_k|| < tolerance, the residual against the size of the
// solver output it belongs to (preCICE's relative convergence measure). Unlike relative_norm it
// needs no step history, so it means the same in every iteration and every scheme: side by
// side the first displacement residual can be near zero while the loads' is not. An output of
// exactly zero with a zero residual counts as converged.
#include <fmt/format.h>

#include "coupler/convergence/norm_criterion.hpp"

namespace cocopp {
namespace {

class ValueRelativeNorm : public NormCriterion {
 public:
  explicit ValueRelativeNorm(const Settings& s) : NormCriterion(s, true) {}
  /// No line a plot of ||r|| could draw: the bound moves with the values.
  std::vector<Tolerance> tolerances() const override { return {}; }
  void initialize_step() override { last_ = -1.0; }
  void set_output(const Eigen::VectorXd& output) override { output_ = norm(output); }
  void update(const Eigen::VectorXd& r) override {
    const double residual = norm(r);
    last_ = residual == 0.0 ? 0.0 : residual / output_;  // inf for a zero output
  }
  bool is_satisfied() const override { return last_ >= 0.0 && last_ < tolerance_; }
  std::string progress() const override {
    if (last_ < 0.0) return "";
    return fmt::format("of the values{} {:.2e}", order_ == "2" ? "" : " (" + order_ + ")", last_);
  }
  std::string describe() const override {
    return fmt::format("value_relative_norm({}) < {:g}", order_, tolerance_);
  }

 private:
  double output_ = 0.0;
  double last_ = -1.0;
};

}  // namespace

COCOPP_REGISTER(ConvergenceCriterionRegistry, "value_relative_norm", ValueRelativeNorm)

}  // namespace cocopp
