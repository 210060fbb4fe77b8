#pragma once
// The part of absolute_norm and relative_norm they share: the norm order (1, 2 or inf) and the
// tolerance.
#include <Eigen/Core>
#include <string>

#include "coupler/convergence/convergence_criterion.hpp"

namespace cocopp {

class NormCriterion : public ConvergenceCriterion {
 public:
  NormCriterion(const Settings& s, bool relative)
      : tolerance_(s.required_in_range("tolerance", Range::non_negative())),
        order_(s.get_choice("order", "2", {"1", "2", "inf"})),
        relative_(relative) {}
  std::vector<Tolerance> tolerances() const override { return {{relative_, order_, tolerance_}}; }

 protected:
  double norm(const Eigen::VectorXd& r) const {
    if (order_ == "1") return r.lpNorm<1>();
    if (order_ == "inf") return r.lpNorm<Eigen::Infinity>();
    return r.norm();
  }
  double tolerance_;
  std::string order_;
  bool relative_;
};

}  // namespace cocopp
