#pragma once
// The coupled-solver state in its own HDF5 file next to the results (<name>.state.h5), written
// at the end of a run and, if asked, every few steps. Writing goes to a temporary file that
// is renamed over the old one, so a run killed while writing leaves the previous state intact.
//
// Layout: root attributes `step` (the last completed time step), `time`, `coupled_solver`
// (its description), `cocopp_version`; one group per State node, one float64 dataset per
// array (scalar, 1D or rows x columns). Readable with h5py; see docs/results.md.
#include <filesystem>
#include <string>

#include "coupler/results/state.hpp"

namespace cocopp {

struct SavedState {
  State state;
  int step = 0;
  double time = 0.0;
  std::string coupled_solver;
};

/// Throws std::runtime_error naming the file if it cannot be written.
void write_state_file(const std::filesystem::path& file, const SavedState& saved);
/// Throws std::runtime_error naming the file if it is missing or not a state file.
SavedState read_state_file(const std::filesystem::path& file);

}  // namespace cocopp
