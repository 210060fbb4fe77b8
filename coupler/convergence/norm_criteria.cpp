// absolute_norm and relative_norm: tolerances on a norm of the residual.
#include <fmt/format.h>

#include <Eigen/Core>

#include "coupler/convergence/convergence_criterion.hpp"

namespace cocopp {
namespace {

/// Shared by both: the norm order (1, 2 or inf) and the tolerance.
class NormCriterion : public ConvergenceCriterion {
 public:
  explicit NormCriterion(const Settings& s)
      : tolerance_(s.required_in_range("tolerance", Range::non_negative())),
        order_(s.get_choice("order", "2", {"1", "2", "inf"})) {}

 protected:
  double norm(const Eigen::VectorXd& r) const {
    if (order_ == "1") return r.lpNorm<1>();
    if (order_ == "inf") return r.lpNorm<Eigen::Infinity>();
    return r.norm();
  }
  double tolerance_;
  std::string order_;
};

class AbsoluteNorm : public NormCriterion {
 public:
  using NormCriterion::NormCriterion;
  void initialize_step() override { last_ = -1.0; }
  void update(const Eigen::VectorXd& r) override { last_ = norm(r); }
  bool is_satisfied() const override { return last_ >= 0.0 && last_ < tolerance_; }
  std::string describe() const override {
    return fmt::format("absolute_norm({}) < {:g}", order_, tolerance_);
  }

 private:
  double last_ = -1.0;
};

/// ||r_k|| / ||r_1|| < tolerance, with r_1 the first residual of the time step. A first residual
/// of exactly zero means the prediction already solves the step: that counts as converged.
class RelativeNorm : public NormCriterion {
 public:
  using NormCriterion::NormCriterion;
  void initialize_step() override { first_ = last_ = -1.0; }
  void update(const Eigen::VectorXd& r) override {
    last_ = norm(r);
    if (first_ < 0.0) first_ = last_;
  }
  bool is_satisfied() const override {
    if (last_ < 0.0) return false;
    if (first_ == 0.0) return true;
    return last_ / first_ < tolerance_;
  }
  std::string describe() const override {
    return fmt::format("relative_norm({}) < {:g}", order_, tolerance_);
  }

 private:
  double first_ = -1.0;
  double last_ = -1.0;
};

}  // namespace

COCOPP_REGISTER(ConvergenceCriterionRegistry, "absolute_norm", AbsoluteNorm)
COCOPP_REGISTER(ConvergenceCriterionRegistry, "relative_norm", RelativeNorm)

}  // namespace cocopp
