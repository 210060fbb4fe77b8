// The SDK sizes interface data with its own copy of the variable table (it cannot link the
// coupler); this keeps the two copies in step.
#include <gtest/gtest.h>

#include "coupler/data/variables.hpp"
#include "solver_wrappers/protocol/variable_components.hpp"

namespace cocopp {
namespace {

TEST(VariableTableTest, ProtocolAndCouplerAgreeOnComponents) {
  for (const auto& variable : variable_table())
    EXPECT_EQ(protocol::variable_components(variable.name), variable.components)
        << "variable '" << variable.name
        << "': update solver_wrappers/protocol/variable_components.cpp";
  EXPECT_EQ(protocol::variable_components("no_such_variable"), 0);
}

}  // namespace
}  // namespace cocopp
