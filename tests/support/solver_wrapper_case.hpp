#pragma once
// A solver wrapper of a test, made as a case file would make it: from one wrapper's keys, for a
// case in `directory` with time step `delta_t`, and initialized (its solver started), at the
// start or (`timestep_start`) as a restart after that step.
#include <filesystem>
#include <memory>
#include <string>

#include "core/case/settings.hpp"
#include "solver_wrappers/solver_wrapper.hpp"

namespace cocopp::testing {

inline std::unique_ptr<SolverWrapper> initialized_wrapper(const std::string& keys,
                                                          const std::filesystem::path& directory,
                                                          double delta_t, int timestep_start = 0) {
  RunSettings run;
  run.delta_t = delta_t;
  run.case_directory = directory;
  run.timestep_start = timestep_start;  // > 0: a restart after that step
  const Settings settings = Settings::load_string(keys, "case.yaml");
  auto wrapper = SolverWrapperRegistry::instance().create(settings, run);
  settings.check_unused_keys();
  wrapper->initialize();
  return wrapper;
}

}  // namespace cocopp::testing
