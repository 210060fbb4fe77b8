#pragma once
// RunFiles: the names of the files a run writes, spelt in this one place. A run writes into
// settings.results_directory, every file named after settings.results_name (the case file's
// stem by default):
//
//   <name>.h5                         the results (HDF5, ResultsWriter; docs/results.md)
//   <name>.summary.json               the run summary (RunSummary)
//   <name>.state.h5                   the coupled solver's state, for a restart (state_file.hpp)
//   <name>.lock                       held while a run of the case goes (CaseLock)
//   <name>.pvd, <name>_vtk/           the interface for ParaView every step (VtkSeries)
//   <name>_step<N>_iterations.pvd     ... every coupling iteration of step N
//   <name>_watchpoint_<point>.csv     a watchpoint's values every step (WatchpointCsv)
#include <filesystem>
#include <string>
#include <vector>

namespace cocopp {

struct RunFiles {
  std::filesystem::path directory;
  std::string name;

  std::filesystem::path results() const { return file(".h5"); }
  std::filesystem::path summary() const { return file(".summary.json"); }
  std::filesystem::path state() const { return file(".state.h5"); }
  std::filesystem::path lock() const { return file(".lock"); }
  /// The files a run creates or replaces whole: none may be a link (a planted one would make
  /// the run overwrite its target).
  std::vector<std::filesystem::path> replaced() const { return {results(), summary(), state()}; }
  /// The stems of VtkSeries (<stem>.pvd and <stem>_vtk/ in `directory`).
  std::string vtk_series() const { return name; }
  std::string iteration_vtk_series(int step) const;
  std::filesystem::path watchpoint_csv(const std::string& watchpoint) const {
    return directory / (name + "_watchpoint_" + watchpoint + ".csv");
  }

 private:
  std::filesystem::path file(const char* extension) const { return directory / (name + extension); }
};

}  // namespace cocopp
