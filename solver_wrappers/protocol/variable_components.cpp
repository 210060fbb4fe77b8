#include "solver_wrappers/protocol/variable_components.hpp"

#include <utility>

namespace cocopp::protocol {

int variable_components(const std::string& variable) {
  static const std::pair<const char*, int> table[] = {
      {"displacement", 3}, {"pressure", 1},    {"traction", 3},  {"force", 3},
      {"velocity", 3},     {"temperature", 1}, {"heat_flux", 1},
  };
  for (const auto& [name, components] : table)
    if (variable == name) return components;
  return 0;
}

}  // namespace cocopp::protocol
