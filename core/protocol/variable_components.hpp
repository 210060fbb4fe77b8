#pragma once
// The table of interface variables (name, components per point, unit): the one table both the
// coupler (core/data/variables.hpp) and the solver SDK use. It lives at the protocol level
// because the SDK depends on the standard library only, so that any solver can link it.
#include <string>
#include <vector>

namespace cocopp::protocol {

struct VariableDefinition {
  const char* name;
  int components;  ///< 1 for scalars, 3 for vectors
  const char* unit;
};

/// Every variable an interface can carry. Add a row here to add a variable, and the same to
/// solvers/sdk/cocopp_sdk.py and docs/protocol.md (ctest protocol_tables compares them).
const std::vector<VariableDefinition>& variable_definitions();

/// Components of `variable`, or 0 if the name is unknown.
int variable_components(const std::string& variable);

}  // namespace cocopp::protocol
