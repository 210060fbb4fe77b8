#pragma once
// WatchpointCsv: each watchpoint's values as a CSV file a spreadsheet or pandas reads as it is,
// one row per step, written and flushed step by step while the run goes:
//
//   <directory>/<name>_watchpoint_<watchpoint>.csv   (RunFiles::watchpoint_csv)
//   step,time,displacement_x,displacement_y,displacement_z,pressure,traction_x,...
//
// Values in full precision (the shortest text that reads back to the same double). A restarted run
// keeps the rows up to the step it continues after and appends from there.
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "core/data/interface.hpp"
#include "coupler/results/run_files.hpp"

namespace cocopp {

class WatchpointCsv {
 public:
  /// One file per model part of `layout` (Watchpoints::layout()), created with its header; with
  /// `continue_after_step` >= 0, the files of an earlier run cut after that step and continued.
  WatchpointCsv(const RunFiles& files, const Interface& layout, int continue_after_step = -1);

  void write_step(int step, double time, const Interface& values);

  const std::vector<std::filesystem::path>& files() const { return paths_; }

 private:
  std::vector<std::filesystem::path> paths_;
  std::vector<std::unique_ptr<std::ofstream>> files_;
};

}  // namespace cocopp
