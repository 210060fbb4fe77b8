#include "core/protocol/variable_components.hpp"

namespace cocopp::protocol {

const std::vector<VariableDefinition>& variable_definitions() {
  static const std::vector<VariableDefinition> table = {
      {"displacement", 3, "m"},
      {"pressure", 1, "Pa"},
      {"traction", 3, "Pa"},
      {"force", 3, "N"},
      {"velocity", 3, "m/s"},
      {"temperature", 1, "K"},
      {"heat_flux", 1, "W/m2"},
      // A lubricant film's thickness and wall position, and the fraction of a face another
      // mesh covers: what a structure driven by displacement under a film takes
      // (solver_wrappers/calculix/displacement_drive.hpp).
      {"gap", 1, "m"},
      {"wall_displacement", 3, "m"},
      {"coverage", 1, "1"},
      // 1 where such a structure drives its node, 0 where the node is loaded: a mapped
      // wrapper's exact round trip takes the loaded ones' displacement as it is.
      {"driven", 1, "1"},
  };
  return table;
}

int variable_components(const std::string& variable) {
  for (const auto& definition : variable_definitions())
    if (variable == definition.name) return definition.components;
  return 0;
}

}  // namespace cocopp::protocol
