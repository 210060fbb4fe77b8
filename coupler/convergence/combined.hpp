#pragma once
// The part of `and` and `or` they share: a list of any criteria, nested as deep as needed.
#include <memory>
#include <vector>

#include "core/case/suggest.hpp"
#include "coupler/convergence/convergence_criterion.hpp"

namespace cocopp {

class Combined : public ConvergenceCriterion {
 public:
  Combined(const Settings& s, bool all) : all_(all) {
    for (const auto& child : s.list("criteria"))
      criteria_.push_back(ConvergenceCriterionRegistry::instance().create(child));
    if (criteria_.empty()) s.fail("criteria", "needs at least one criterion");
  }
  void attach_solvers(const std::array<SolverWrapper*, 2>& solvers) override {
    for (auto& c : criteria_) c->attach_solvers(solvers);
  }
  void initialize_step() override {
    for (auto& c : criteria_) c->initialize_step();
  }
  void set_output(const Eigen::VectorXd& output) override {
    for (auto& c : criteria_) c->set_output(output);
  }
  void update(const Eigen::VectorXd& r) override {
    for (auto& c : criteria_) c->update(r);
  }
  bool is_satisfied() const override {
    return combine([](const ConvergenceCriterion& c) { return c.is_satisfied(); });
  }
  /// Stopped and at least one tolerance (not only an iteration limit) is met.
  bool tolerance_met() const override {
    if (!is_satisfied()) return false;
    for (const auto& c : criteria_)
      if (c->tolerance_met()) return true;
    return false;
  }
  bool limit_reached() const override {
    for (const auto& c : criteria_)
      if (c->limit_reached()) return true;
    return false;
  }
  std::string progress() const override {
    std::vector<std::string> parts;
    for (const auto& c : criteria_)
      if (auto part = c->progress(); !part.empty()) parts.push_back(std::move(part));
    return join(parts, ", ");
  }
  std::vector<Tolerance> tolerances() const override {
    std::vector<Tolerance> all;
    for (const auto& c : criteria_)
      for (const auto& t : c->tolerances()) all.push_back(t);
    return all;
  }
  std::string describe() const override {
    std::vector<std::string> parts;
    for (const auto& c : criteria_) parts.push_back(c->describe());
    return "(" + join(parts, all_ ? " and " : " or ") + ")";
  }

 private:
  template <class Test>
  bool combine(Test test) const {
    for (const auto& c : criteria_)
      if (test(*c) != all_) return !all_;
    return all_;
  }
  bool all_;
  std::vector<std::unique_ptr<ConvergenceCriterion>> criteria_;
};

}  // namespace cocopp
