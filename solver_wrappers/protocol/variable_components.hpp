#pragma once
// Components per point of each interface variable, as the solver side needs them to size the
// data it exchanges. The protocol cannot use the coupler's table (coupler/data/variables.cpp):
// it depends on the standard library only, so that any solver can link the SDK. A unit test
// (tests/unit/protocol) checks that both tables agree.
#include <string>

namespace cocopp::protocol {

/// Components of `variable` (1 for scalars, 3 for vectors), or 0 if the name is unknown.
int variable_components(const std::string& variable);

}  // namespace cocopp::protocol
