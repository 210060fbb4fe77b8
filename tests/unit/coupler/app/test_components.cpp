// `cocopp components`: every kind of component a case file can name is listed, with every type
// the registries hold, in a cocopp linked as the executable is.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>

#include "coupler/app/components.hpp"

using namespace cocopp;

namespace {

std::map<std::string, std::vector<std::string>> listed() {
  std::map<std::string, std::vector<std::string>> by_kind;
  for (const ComponentKind& kind : component_kinds()) by_kind[kind.description] = kind.types;
  return by_kind;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

TEST(Components, EveryKindACaseCanNameIsListed) {
  const auto kinds = listed();
  for (const char* kind :
       {"coupled solvers", "coupling schemes", "models", "predictors", "convergence criteria",
        "solver wrappers", "interpolators", "transformers", "outputs"}) {
    ASSERT_TRUE(kinds.count(kind)) << kind;
    EXPECT_FALSE(kinds.at(kind).empty()) << kind;
  }
  EXPECT_EQ(kinds.size(), 9u);
}

TEST(Components, EveryTypeIsRegistered) {
  const std::map<std::string, std::vector<std::string>> expected = {
      {"coupled solvers", {"aitken", "explicit", "gauss_seidel", "ibqn", "iqni", "relaxation"}},
      {"coupling schemes", {"parallel", "serial"}},
      {"models", {"ls", "mv", "mvmf"}},
      {"predictors", {"constant", "cubic", "legacy", "linear", "quadratic"}},
      {"convergence criteria", {"absolute_norm", "and", "iteration_limit", "or", "relative_norm"}},
      {"solver wrappers",
       {"calculix", "mapped", "openfoam", "process", "tube_flow", "tube_ringmodel",
        "tube_structure"}},
      {"interpolators", {"linear", "nearest", "radial_basis"}},
      {"transformers",
       {"axisymmetric_2d_to_3d", "axisymmetric_3d_to_2d", "depth_2d_to_3d", "depth_3d_to_2d",
        "permutation"}},
      {"outputs", {"hdf5", "paraview", "paraview_iterations", "watchpoint_csv"}},
  };
  const auto kinds = listed();
  for (const auto& [kind, names] : expected)
    for (const auto& name : names)
      EXPECT_TRUE(contains(kinds.at(kind), name)) << kind << ": " << name;
}
