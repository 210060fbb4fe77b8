#pragma once
// The table of interface variables: a name and its number of components per point.
#include <string>
#include <vector>

namespace cocopp {

struct VariableInfo {
  std::string name;
  int components;
  std::string unit;
};

/// All variables an interface can carry (the table is
/// core/protocol/variable_components.cpp).
const std::vector<VariableInfo>& variable_table();

/// The variable called `name`; throws std::invalid_argument naming the nearest known variable.
const VariableInfo& variable_info(const std::string& name);

}  // namespace cocopp
