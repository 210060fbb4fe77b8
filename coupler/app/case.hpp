#pragma once
// A case: the components a case file names, built and validated, not yet started.
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "core/case/settings.hpp"
#include "coupler/coupled_solvers/coupled_solver.hpp"
#include "coupler/outputs/run_output.hpp"
#include "coupler/results/run_files.hpp"
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
  RunFiles files;             ///< settings.results_directory and results_name: what a run writes
  std::string results_where;  ///< "case.yaml:4:3: 'settings.results_directory'" for messages
  Watchpoints watchpoints;    ///< settings.watchpoints: variables at points, every step
  /// What the case's settings ask the run to write besides the summary (create_outputs(): the
  /// HDF5 results, ParaView, the watchpoints' CSV files, ...).
  std::vector<std::unique_ptr<RunOutput>> outputs;
  int state_interval = 0;  ///< also save the coupled-solver state every this many steps
  /// The solvers' working directories named in the case (the run locks them).
  std::vector<std::filesystem::path> working_directories;
  /// A restarted run: the saved state it continues from (run.timestep_start is its step).
  std::optional<SavedState> restart;
  double end_time() const { return run.delta_t * (run.timestep_start + run.number_of_timesteps); }
};

/// Read and validate a case file (YAML or JSON): every component is created, every key
/// checked. Throws CaseError naming the file, line and key.
///
/// A restart continues a run from its saved state (RunFiles::state()): with `restart`
/// from the step the state file holds, and with settings.timestep_start > 0 from that step
/// (the state file must hold it). The run then ends where the case ends (timestep_start +
/// number_of_timesteps, or end_time), and the solvers are created to start after the restart
/// step. Throws std::runtime_error if there is no such state or nothing is left to run.
Case load_case(const std::filesystem::path& file, bool restart = false);

}  // namespace cocopp
