// `absolute_norm`: ||r_k|| < tolerance.
#include <fmt/format.h>

#include "coupler/convergence/norm_criterion.hpp"

namespace cocopp {
namespace {

class AbsoluteNorm : public NormCriterion {
 public:
  explicit AbsoluteNorm(const Settings& s) : NormCriterion(s, false) {}
  void initialize_step() override { last_ = -1.0; }
  void update(const Eigen::VectorXd& r) override { last_ = norm(r); }
  bool is_satisfied() const override { return last_ >= 0.0 && last_ < tolerance_; }
  std::string progress() const override {
    if (order_ == "2" || last_ < 0.0) return "";
    return fmt::format("{}-norm {:.3e}", order_, last_);
  }
  std::string describe() const override {
    return fmt::format("absolute_norm({}) < {:g}", order_, tolerance_);
  }

 private:
  double last_ = -1.0;
};

}  // namespace

COCOPP_REGISTER(ConvergenceCriterionRegistry, "absolute_norm", AbsoluteNorm)

}  // namespace cocopp
