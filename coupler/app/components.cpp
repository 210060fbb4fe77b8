#include "coupler/app/components.hpp"

#include <fmt/format.h>

#include "core/case/suggest.hpp"
#include "coupler/convergence/convergence_criterion.hpp"
#include "coupler/coupled_solvers/coupled_solver.hpp"
#include "coupler/coupled_solvers/models/model.hpp"
#include "coupler/outputs/run_output.hpp"
#include "coupler/predictors/predictor.hpp"
#include "mappers/interpolators/interpolator.hpp"
#include "mappers/transformers/transformer.hpp"
#include "solver_wrappers/solver_wrapper.hpp"

namespace cocopp {

std::vector<ComponentKind> component_kinds() {
  return {
      {"coupled solvers", "coupled_solver.type", CoupledSolverRegistry::instance().names()},
      {"coupling schemes", "coupled_solver.scheme", CouplingSchemeRegistry::instance().names()},
      {"models", "coupled_solver.model.type", ModelRegistry::instance().names()},
      {"predictors", "coupled_solver.predictor.type", PredictorRegistry::instance().names()},
      {"convergence criteria", "coupled_solver.convergence_criterion.type",
       ConvergenceCriterionRegistry::instance().names()},
      {"solver wrappers", "solver_wrappers[].type", SolverWrapperRegistry::instance().names()},
      {"interpolators", "solver_wrappers[].{input,output}_mapper.type",
       InterpolatorRegistry::instance().names()},
      {"transformers", "solver_wrappers[].{input,output}_mapper.transformers[].type",
       TransformerRegistry::instance().names()},
      {"outputs", "settings: results_write_interval, vtk_output, vtk_iterations, watchpoints",
       RunOutputRegistry::instance().names()},
  };
}

void print_components() {
  for (const ComponentKind& kind : component_kinds())
    fmt::print("{} ({}): {}\n", kind.description, kind.key, join(kind.types));
}

}  // namespace cocopp
