#pragma once
// A case: the components a case file names, built and validated, not yet started.
#include <filesystem>
#include <memory>
#include <vector>

#include "core/case/settings.hpp"
#include "coupler/coupled_solvers/coupled_solver.hpp"
#include "solver_wrappers/solver_wrapper.hpp"

namespace cocopp {

struct Case {
  std::filesystem::path file;
  RunSettings run;
  std::string coupled_solver_type;
  std::unique_ptr<CoupledSolver> coupled_solver;
  std::vector<std::unique_ptr<SolverWrapper>> solvers;  ///< exactly two: F (x -> y), S (y -> x)
  std::filesystem::path results_directory;
  std::string results_name;  ///< file stem of the HDF5 file and the JSON summary
  int state_interval = 0;    ///< also save the coupled-solver state every this many steps
  double end_time() const { return run.delta_t * (run.timestep_start + run.number_of_timesteps); }
};

/// Read and validate a case file (YAML or JSON): every component is created, every key
/// checked. Throws CaseError naming the file, line and key.
Case load_case(const std::filesystem::path& file);

}  // namespace cocopp
