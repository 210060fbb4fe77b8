// The built-in tube solvers as case-file types: `tube_flow`, `tube_structure` and
// `tube_ringmodel` are `process` solvers whose command defaults to the executable built next
// to cocopp and its input file, e.g. [<bin>/cocopp-tube-flow, tube_flow.yaml]; the key
// `input_file` changes the file name.
#include "solver_wrappers/process/process_solver_wrapper.hpp"
#include "solver_wrappers/tube/tube_flow.hpp"
#include "solver_wrappers/tube/tube_input.hpp"
#include "solver_wrappers/tube/tube_ringmodel.hpp"
#include "solver_wrappers/tube/tube_structure.hpp"

namespace cocopp {
namespace {

/// `cocopp check` reads the input file as the solver will (a typo there is found before
/// `run`).
template <class Parameters>
void check_input_file(const std::filesystem::path& file) {
  (void)tube::load_input_file<Parameters>(file.string());
}

/// The tube solvers answer a request in tens of microseconds: waiting for the next one
/// without sleeping saves a process wake-up per request (docs/solver-wrappers.md).
constexpr double kBuiltinSolverBusyWait = 1e-3;

bool register_builtin_solver(const std::string& type, const std::string& executable,
                             const std::string& input_file,
                             std::function<void(const std::filesystem::path&)> check_input) {
  return SolverWrapperRegistry::instance().add_at_start_up(
      type, __FILE__,
      [=](const Settings& settings, const RunSettings& run) -> std::unique_ptr<SolverWrapper> {
        return std::make_unique<ProcessSolverWrapper>(
            settings, run,
            DefaultCommand{builtin_solver_directory() / executable,
                           input_file,
                           {},
                           {},
                           check_input,
                           kBuiltinSolverBusyWait});
      });
}

const bool registered_tube_flow = register_builtin_solver(
    "tube_flow", "cocopp-tube-flow", "tube_flow.yaml", check_input_file<tube::TubeFlowParameters>);
const bool registered_tube_structure =
    register_builtin_solver("tube_structure", "cocopp-tube-structure", "tube_structure.yaml",
                            check_input_file<tube::TubeStructureParameters>);
const bool registered_tube_ringmodel =
    register_builtin_solver("tube_ringmodel", "cocopp-tube-ringmodel", "tube_ringmodel.yaml",
                            check_input_file<tube::TubeRingmodelParameters>);

}  // namespace

}  // namespace cocopp
