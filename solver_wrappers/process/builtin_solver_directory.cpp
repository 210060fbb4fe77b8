// Where the built-in solver executables are (the tube solvers, cocoppPimpleFoam): next to the
// running cocopp, or in COCOPP_BIN_DIR.
#include <cstdlib>

#include "solver_wrappers/process/process_solver_wrapper.hpp"

namespace cocopp {

std::filesystem::path builtin_solver_directory() {
  // Tests run from their own directories, so they point here with COCOPP_BIN_DIR.
  if (const char* directory = std::getenv("COCOPP_BIN_DIR"); directory && *directory)
    return directory;
  std::error_code error;
  const auto executable = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? std::filesystem::path() : executable.parent_path();
}

}  // namespace cocopp
