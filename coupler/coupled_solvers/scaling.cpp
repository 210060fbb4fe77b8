#include "coupler/coupled_solvers/scaling.hpp"

#include <fmt/format.h>

#include <cmath>
#include <set>

#include "core/case/suggest.hpp"

namespace cocopp {

VariableScaling::VariableScaling(const Settings& s, bool residual_sum_by_default) : settings_(s) {
  if (!s.has("scaling")) {
    residual_sum_ = residual_sum_by_default;
    return;
  }
  if (s.node()["scaling"].IsScalar()) {
    const auto mode = s.required_choice("scaling", {"automatic", "residual_sum", "none"});
    automatic_ = mode == "automatic";
    residual_sum_ = mode == "residual_sum";
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
  Eigen::Index offset = 0;
  for (const Interface* layout : layouts) {
    layouts_.push_back({layout->blocks(), Eigen::VectorXd::Ones(layout->size()), offset});
    offset += layout->size();
    for (const auto& block : layout->blocks()) present.insert(block.variable);
  }
  field_sums_.assign(layouts_.size(), 0.0);
  field_weights_.assign(layouts_.size(), 1.0);
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
  if (residual_sum_) {  // one weight per field
    for (std::size_t i = 0; i < layouts_.size(); ++i)
      layouts_[i].weights.setConstant(field_weights_[i]);
    return;
  }
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

void VariableScaling::accumulate(const Eigen::VectorXd& r) {
  const double total = r.norm();
  if (!(total > 0.0) || !std::isfinite(total)) return;
  for (std::size_t i = 0; i < layouts_.size(); ++i)
    field_sums_[i] += segment_of(r, layouts_[i]).norm() / total;
}

Eigen::VectorXd VariableScaling::refresh() {
  // A field whose sum is still zero keeps its weight (1 until it has a residual). Weights
  // within 10 % of those in use stay: re-expressing the models' columns costs a QR
  // factorization, and any fixed weights are as consistent as new ones.
  std::vector<double> candidate = field_weights_;
  bool changed = false;
  for (std::size_t i = 0; i < layouts_.size(); ++i) {
    if (!(field_sums_[i] > 0.0)) continue;
    candidate[i] = 1.0 / field_sums_[i];
    if (std::abs(candidate[i] / field_weights_[i] - 1.0) > 0.1) changed = true;
  }
  if (!changed) return {};
  const Eigen::VectorXd old = stacked_weights();
  field_weights_ = std::move(candidate);
  refresh_weights();
  return stacked_weights().cwiseQuotient(old);
}

Eigen::VectorXd VariableScaling::apply_all(const Eigen::VectorXd& values) {
  if (!enabled()) return values;
  if (automatic_)
    for (const Layout& layout : layouts_) fix_automatic_weights(layout, segment_of(values, layout));
  return values.cwiseProduct(stacked_weights());
}

Eigen::VectorXd VariableScaling::remove_all(const Eigen::VectorXd& weighted) const {
  if (!enabled()) return weighted;
  return weighted.cwiseQuotient(stacked_weights());
}

Eigen::VectorXd VariableScaling::stacked_weights() const {
  Eigen::Index size = 0;
  for (const Layout& layout : layouts_) size += layout.weights.size();
  Eigen::VectorXd stacked(size);
  for (const Layout& layout : layouts_) segment_of(stacked, layout) = layout.weights;
  return stacked;
}

void VariableScaling::save_state(State& state) const {
  if (residual_sum_) {  // per field: its sum and the weight in use
    for (std::size_t i = 0; i < field_sums_.size(); ++i) {
      state.group("sums").set(std::to_string(i), field_sums_[i]);
      state.group("weights").set(std::to_string(i), field_weights_.at(i));
    }
    return;
  }
  for (const auto& [variable, weight] : weights_) state.set(variable, weight);
}

void VariableScaling::load_state(const State& state) {
  if (residual_sum_) {
    for (std::size_t i = 0; i < layouts_.size(); ++i)
      if (state.has_group("sums") && state.group("sums").has(std::to_string(i))) {
        field_sums_[i] = state.group("sums").scalar(std::to_string(i));
        field_weights_[i] = state.group("weights").scalar(std::to_string(i));
      }
    refresh_weights();
    return;
  }
  weights_.clear();
  for (const auto& [variable, array] : state.arrays()) weights_[variable] = state.scalar(variable);
  refresh_weights();
}

std::string VariableScaling::describe() const {
  if (automatic_) return "automatic";
  if (residual_sum_) return "residual_sum";
  std::vector<std::string> parts;
  for (const auto& [variable, factor] : fixed_)
    parts.push_back(fmt::format("{} {:g}", variable, factor));
  return join(parts);
}

}  // namespace cocopp
