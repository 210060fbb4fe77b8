#include "coupler/results/run_files.hpp"

#include <fmt/format.h>

namespace cocopp {

std::string RunFiles::iteration_vtk_series(int step) const {
  return fmt::format("{}_step{:06d}_iterations", name, step);
}

}  // namespace cocopp
