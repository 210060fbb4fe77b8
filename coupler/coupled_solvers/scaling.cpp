#include "coupler/coupled_solvers/scaling.hpp"

#include <fmt/format.h>

#include <cmath>
#include <set>

#include "core/case/suggest.hpp"

namespace cocopp {

VariableScaling::VariableScaling(const Settings& s) : settings_(s) {
  if (!s.has("scaling")) return;
  if (s.node()["scaling"].IsScalar()) {
    s.required_choice("scaling", {"automatic"});
    automatic_ = true;
    return;
  }
  const Settings factors = s.child("scaling");
  for (const auto& entry : factors.node()) {
    const auto variable = entry.first.as<std::string>();
    fixed_[variable] = factors.required_in_range(variable, Range::positive());
  }
  weights_ = fixed_;
}

void VariableScaling::bind(const std::vector<const Interface*>& layouts) {
  std::set<std::string> present;
  layouts_.clear();
  for (const Interface* layout : layouts) {
    layouts_.push_back({layout->blocks(), Eigen::VectorXd::Ones(layout->size())});
    for (const auto& block : layout->blocks()) present.insert(block.variable);
  }
  const std::vector<std::string> names(present.begin(), present.end());
  for (const auto& [variable, factor] : fixed_)
    if (!present.count(variable))
      settings_.child("scaling").fail(
          variable, fmt::format("no variable '{}' on the interface of the coupling (it has: "
                                "{}){}",
                                variable, join(names), did_you_mean(variable, names)));
  refresh_weights();
}

void VariableScaling::refresh_weights() {
  for (Layout& layout : layouts_)
    for (const auto& block : layout.blocks) {
      const auto found = weights_.find(block.variable);
      const double weight = found == weights_.end() ? 1.0 : found->second;
      layout.weights.segment(block.offset, block.points * block.components).setConstant(weight);
    }
}

void VariableScaling::fix_automatic_weights(const Layout& layout, const Eigen::VectorXd& values) {
  // Sum of squares and count per variable over all model parts.
  std::map<std::string, std::pair<double, Eigen::Index>> sums;
  for (const auto& block : layout.blocks) {
    if (weights_.count(block.variable)) continue;
    const Eigen::Index size = block.points * block.components;
    auto& [squares, count] = sums[block.variable];
    squares += values.segment(block.offset, size).squaredNorm();
    count += size;
  }
  bool changed = false;
  for (const auto& [variable, sum] : sums)
    if (sum.first > 0.0 && std::isfinite(sum.first)) {
      weights_[variable] = 1.0 / std::sqrt(sum.first / double(sum.second));
      changed = true;
    }
  if (changed) refresh_weights();
}

Eigen::VectorXd VariableScaling::apply(std::size_t index, const Eigen::VectorXd& values) {
  if (!enabled()) return values;
  const Layout& layout = layouts_.at(index);
  if (automatic_) fix_automatic_weights(layout, values);
  return layout.weights.cwiseProduct(values);
}

Eigen::VectorXd VariableScaling::remove(std::size_t index, const Eigen::VectorXd& weighted) const {
  if (!enabled()) return weighted;
  return weighted.cwiseQuotient(layouts_.at(index).weights);
}

void VariableScaling::save_state(State& state) const {
  for (const auto& [variable, weight] : weights_) state.set(variable, weight);
}

void VariableScaling::load_state(const State& state) {
  weights_.clear();
  for (const auto& [variable, array] : state.arrays()) weights_[variable] = state.scalar(variable);
  refresh_weights();
}

std::string VariableScaling::describe() const {
  if (automatic_) return "automatic";
  std::vector<std::string> parts;
  for (const auto& [variable, factor] : fixed_)
    parts.push_back(fmt::format("{} {:g}", variable, factor));
  return join(parts);
}

}  // namespace cocopp
