#include "core/data/interface.hpp"

#include <set>
#include <stdexcept>

#include "core/data/variables.hpp"

namespace cocopp {

Interface::Interface(std::vector<Part> parts) : parts_(std::move(parts)) {
  Eigen::Index offset = 0;
  std::set<std::string> seen;
  for (const auto& part : parts_) {
    if (!part.model_part) throw std::invalid_argument("interface part without a model part");
    if (!seen.insert(part.model_part->name).second)
      throw std::invalid_argument("model part '" + part.model_part->name +
                                  "' appears twice in one interface");
    const auto points = static_cast<Eigen::Index>(part.model_part->size());
    for (const auto& variable : part.variables) {
      const int components = variable_info(variable).components;
      blocks_.push_back({part.model_part->name, variable, offset, points, components});
      offset += points * components;
    }
  }
  data_ = Eigen::VectorXd::Zero(offset);
}

void Interface::set_data(const Eigen::VectorXd& values) {
  if (values.size() != data_.size())
    throw std::invalid_argument("interface data of size " + std::to_string(values.size()) +
                                " given where " + std::to_string(data_.size()) +
                                " values are expected (" + describe() + ")");
  data_ = values;
}

const Interface::Block& Interface::block(const std::string& model_part,
                                         const std::string& variable) const {
  for (const auto& b : blocks_)
    if (b.model_part == model_part && b.variable == variable) return b;
  throw std::out_of_range("interface has no variable '" + variable + "' on model part '" +
                          model_part + "' (it has: " + describe() + ")");
}

Eigen::Map<RowMatrix> Interface::values(const std::string& model_part,
                                        const std::string& variable) {
  const Block& b = block(model_part, variable);
  return {data_.data() + b.offset, b.points, b.components};
}

Eigen::Map<const RowMatrix> Interface::values(const std::string& model_part,
                                              const std::string& variable) const {
  const Block& b = block(model_part, variable);
  return {data_.data() + b.offset, b.points, b.components};
}

bool Interface::same_layout(const Interface& other) const {
  if (blocks_.size() != other.blocks_.size()) return false;
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    const Block& a = blocks_[i];
    const Block& b = other.blocks_[i];
    if (a.model_part != b.model_part || a.variable != b.variable || a.points != b.points)
      return false;
  }
  return true;
}

std::string Interface::describe() const {
  std::string out;
  for (const auto& b : blocks_) {
    if (!out.empty()) out += "; ";
    out += b.model_part + ": " + b.variable + " (" + std::to_string(b.points) + " x " +
           std::to_string(b.components) + ")";
  }
  return out.empty() ? "empty" : out;
}

}  // namespace cocopp
