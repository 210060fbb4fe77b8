#pragma once
// A case: the components a case file names, built and validated, not yet started.
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "core/case/settings.hpp"
#include "coupler/coupled_solvers/coupled_solver.hpp"
#include "coupler/results/state_file.hpp"
#include "coupler/results/watchpoints.hpp"
#include "solver_wrappers/solver_wrapper.hpp"

namespace cocopp {

struct Case {
  std::filesystem::path file;
  RunSettings run;
  std::string coupled_solver_type;
  std::unique_ptr<CoupledSolver> coupled_solver;
  std::vector<std::unique_ptr<SolverWrapper>> solvers;  ///< exactly two: F (x -> y), S (y -> x)
  std::filesystem::path results_directory;
  std::string results_where;  ///< "case.yaml:4:3: 'settings.results_directory'" for messages
  std::string results_name;   ///< file stem of the HDF5 file and the JSON summary
  bool vtk_output = false;    ///< also write the interface for ParaView every step (VtkSeries)
  std::vector<int> vtk_iterations;  ///< steps whose every coupling iteration is written too
  Watchpoints watchpoints;          ///< settings.watchpoints: variables at points, every step
  int state_interval = 0;           ///< also save the coupled-solver state every this many steps
  /// s of wall time: steps faster than this are written to the results file together
  double results_write_interval = 0.0;
  /// The solvers' working directories named in the case (the run locks them).
  std::vector<std::filesystem::path> working_directories;
  /// A restarted run: the saved state it continues from (run.timestep_start is its step).
  std::optional<SavedState> restart;
  std::filesystem::path state_file() const {
    return results_directory / (results_name + ".state.h5");
  }
  double end_time() const { return run.delta_t * (run.timestep_start + run.number_of_timesteps); }
};

/// Read and validate a case file (YAML or JSON): every component is created, every key
/// checked. Throws CaseError naming the file, line and key.
///
/// A restart continues a run from its saved state (<results>/<name>.state.h5): with `restart`
/// from the step the state file holds, and with settings.timestep_start > 0 from that step
/// (the state file must hold it). The run then ends where the case ends (timestep_start +
/// number_of_timesteps, or end_time), and the solvers are created to start after the restart
/// step. Throws std::runtime_error if there is no such state or nothing is left to run.
Case load_case(const std::filesystem::path& file, bool restart = false);

}  // namespace cocopp
