// The built-in tube solvers as case-file types: `tube_flow`, `tube_structure` and
// `tube_ringmodel` are `process` solvers whose command defaults to the executable built next
// to cocopp and its input file, e.g. [<bin>/cocopp-tube-flow, tube_flow.yaml]; the key
// `input_file` changes the file name. `cocopp check` has the executable read that file
// (`--check`), as a run would.
#include "solver_wrappers/process/process_solver_wrapper.hpp"

namespace cocopp {
namespace {

/// The tube solvers answer a request in tens of microseconds: waiting for the next one
/// without sleeping saves a process wake-up per request (docs/solver-wrappers.md).
constexpr double kBuiltinSolverBusyWait = 1e-3;

bool register_builtin_solver(const std::string& type, const std::string& executable,
                             const std::string& input_file) {
  return SolverWrapperRegistry::instance().add_at_start_up(
      type, __FILE__,
      [=](const Settings& settings, const RunSettings& run) -> std::unique_ptr<SolverWrapper> {
        return std::make_unique<ProcessSolverWrapper>(
            settings, run,
            DefaultCommand{builtin_solver_directory() / executable, input_file,
                           /*arguments=*/{},
                           /*environment=*/{},
                           /*check_arguments=*/{"--check"}, kBuiltinSolverBusyWait});
      });
}

const bool registered_tube_flow =
    register_builtin_solver("tube_flow", "cocopp-tube-flow", "tube_flow.yaml");
const bool registered_tube_structure =
    register_builtin_solver("tube_structure", "cocopp-tube-structure", "tube_structure.yaml");
const bool registered_tube_ringmodel =
    register_builtin_solver("tube_ringmodel", "cocopp-tube-ringmodel", "tube_ringmodel.yaml");

}  // namespace

}  // namespace cocopp
