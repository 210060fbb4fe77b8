#include "core/data/variables.hpp"

#include <stdexcept>

#include "core/case/suggest.hpp"
#include "core/protocol/variable_components.hpp"

namespace cocopp {

const std::vector<VariableInfo>& variable_table() {
  static const std::vector<VariableInfo> table = [] {
    std::vector<VariableInfo> out;
    for (const auto& d : protocol::variable_definitions())
      out.push_back({d.name, d.components, d.unit});
    return out;
  }();
  return table;
}

const VariableInfo& variable_info(const std::string& name) {
  for (const auto& v : variable_table())
    if (v.name == name) return v;
  std::vector<std::string> names;
  for (const auto& v : variable_table()) names.push_back(v.name);
  throw std::invalid_argument("unknown interface variable '" + name + "'" +
                              did_you_mean(name, names) + " (known: " + join(names) + ")");
}

}  // namespace cocopp
