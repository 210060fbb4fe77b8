#pragma once
// RunSettings: the time settings of a case (its `settings` section), which every component
// that runs steps needs: the solver wrappers, the coupled solver's own solvers.
#include <filesystem>

namespace cocopp {

struct RunSettings {
  double delta_t = 0.0;
  int timestep_start = 0;  ///< > 0: a restarted run, continuing after this step
  int number_of_timesteps = 0;
  std::filesystem::path case_directory;  ///< relative paths in the case are resolved here
};

}  // namespace cocopp
