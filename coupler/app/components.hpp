#pragma once
// `cocopp components`: every component type a case file can name, by kind.
#include <string>
#include <vector>

namespace cocopp {

struct ComponentKind {
  std::string description;  ///< e.g. "predictors"
  std::string key;          ///< where a case names it, e.g. "coupled_solver.predictor.type"
  std::vector<std::string> types;
};

/// Every registry, in the order a case file meets them.
std::vector<ComponentKind> component_kinds();

/// Prints component_kinds(), one kind a line.
void print_components();

}  // namespace cocopp
