#include "core/protocol/variable_components.hpp"

namespace cocopp::protocol {

const std::vector<VariableDefinition>& variable_definitions() {
  static const std::vector<VariableDefinition> table = {
      {"displacement", 3, "m"}, {"pressure", 1, "Pa"},  {"traction", 3, "Pa"},
      {"force", 3, "N"},        {"velocity", 3, "m/s"}, {"temperature", 1, "K"},
      {"heat_flux", 1, "W/m2"},
  };
  return table;
}

int variable_components(const std::string& variable) {
  for (const auto& definition : variable_definitions())
    if (variable == definition.name) return definition.components;
  return 0;
}

}  // namespace cocopp::protocol
