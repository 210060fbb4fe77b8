#include "coupler/data/variables.hpp"

#include <stdexcept>

#include "coupler/case/suggest.hpp"

namespace cocopp {

const std::vector<VariableInfo>& variable_table() {
  static const std::vector<VariableInfo> table = {
      {"displacement", 3, "m"},  {"pressure", 1, "Pa"},   {"traction", 3, "Pa"},
      {"force", 3, "N"},         {"velocity", 3, "m/s"},  {"temperature", 1, "K"},
      {"heat_flux", 1, "W/m2"},
  };
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
