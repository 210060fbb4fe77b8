// `mvmf`: J_prev as the recursion over the columns of the last q steps.
#include <deque>
#include <string>

#include "coupler/coupled_solvers/models/multi_vector.hpp"

namespace cocopp {
namespace {

class MultiVectorMatrixFree : public MultiVector {
 public:
  explicit MultiVectorMatrixFree(const Settings& s)
      : MultiVector(s), reused_steps_(s.get_int_in_range("q", 100, 0)) {}

 protected:
  Eigen::VectorXd apply_previous(const Eigen::VectorXd& y) const override {
    Eigen::VectorXd rest = y;
    Eigen::VectorXd result = Eigen::VectorXd::Zero(y.size());
    for (const StepColumns& step : steps_) result += step.peel(rest);  // newest first
    return result;
  }

  void keep(StepColumns step) override {
    step.freeze();
    steps_.push_front(std::move(step));
    // Dropping the oldest step sets its J_prev, the start of the recursion, to 0.
    while (steps_.size() > std::size_t(reused_steps_)) steps_.pop_back();
  }

  void rescale_previous(const Eigen::VectorXd& factors) override {
    for (StepColumns& step : steps_) {
      step.rescale(factors);
      step.freeze();
    }
  }

  int previous_columns() const override {
    int total = 0;
    for (const StepColumns& step : steps_) total += step.size();
    return total;
  }

  void save_previous(State& state) const override {
    state.set("steps", double(steps_.size()));
    for (std::size_t i = 0; i < steps_.size(); ++i)
      steps_[i].save_state(state.group("step_" + std::to_string(i)));
  }
  void load_previous(const State& state) override {
    steps_.clear();
    const int count = int(state.scalar("steps"));
    for (int i = 0; i < count; ++i) {
      StepColumns step(filter());
      step.load_state(state.group("step_" + std::to_string(i)));
      step.freeze();
      steps_.push_back(std::move(step));
    }
  }

 private:
  int reused_steps_;
  std::deque<StepColumns> steps_;  ///< newest first; steps without columns are not kept
};

}  // namespace

COCOPP_REGISTER(ModelRegistry, "mvmf", MultiVectorMatrixFree)

}  // namespace cocopp
