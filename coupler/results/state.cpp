#include "coupler/results/state.hpp"

#include <stdexcept>

namespace cocopp {

void State::set(const std::string& name, double value) {
  set_array(name, {Eigen::MatrixXd::Constant(1, 1, value), 0});
}

void State::set(const std::string& name, const Eigen::VectorXd& values) {
  set_array(name, {Eigen::MatrixXd(values), 1});
}

void State::set(const std::string& name, Eigen::MatrixXd values) {
  set_array(name, {std::move(values), 2});
}

void State::set_array(const std::string& name, Array array) {
  arrays_[name] = std::move(array);
}

void State::missing(const std::string& what, const std::string& name) const {
  throw std::runtime_error("the saved coupled-solver state has no " + what + " '" +
                           (path_.empty() ? name : path_ + "/" + name) +
                           "': it was written by another coupled solver or model");
}

const Eigen::MatrixXd& State::matrix(const std::string& name) const {
  const auto found = arrays_.find(name);
  if (found == arrays_.end()) missing("array", name);
  return found->second.values;
}

Eigen::VectorXd State::vector(const std::string& name) const {
  const Eigen::MatrixXd& values = matrix(name);
  return Eigen::Map<const Eigen::VectorXd>(values.data(), values.size());
}

double State::scalar(const std::string& name) const {
  const Eigen::MatrixXd& values = matrix(name);
  if (values.size() != 1) missing("scalar", name);
  return values(0, 0);
}

State& State::group(const std::string& name) {
  State& child = groups_[name];
  child.path_ = path_.empty() ? name : path_ + "/" + name;
  return child;
}

const State& State::group(const std::string& name) const {
  const auto found = groups_.find(name);
  if (found == groups_.end()) missing("group", name);
  return found->second;
}

}  // namespace cocopp
