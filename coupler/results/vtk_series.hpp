#pragma once
// VtkSeries: the interface as ParaView reads it. Every model part of a step becomes one VTU file
// (an unstructured grid of its points as vertices, at their initial coordinates, with one point
// array per variable and the point ids), and one PVD collection lists every file with its time
// and part, so that ParaView opens the whole run as a time series (File > Open <name>.pvd;
// "Warp By Vector" with `displacement` shows the deformed interface).
//
//   <directory>/<name>.pvd
//   <directory>/<name>_vtk/<model part>_<step, 6 digits>.vtu
//
// Files are written as a temporary file and renamed (a link planted at a name is replaced,
// never followed), and the collection is rewritten after every step, so that it lists only
// complete files, also while the run goes.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "core/data/interface.hpp"

namespace cocopp {

/// One model part at one step: its points and the values of its variables.
struct VtkPart {
  std::string name;
  std::vector<std::int64_t> ids;
  Coordinates coordinates;
  std::vector<std::pair<std::string, RowMatrix>> fields;  ///< variable -> n_points x components
};

/// The model parts of x and y with their current values, merged by model part name (x's
/// variables first): what the coupler writes for a step.
std::vector<VtkPart> vtk_parts(const Interface& x, const Interface& y);

/// Adds the variables of `values` to the parts of the same name, as fields `prefix<variable>`
/// (the residual of an iteration: "residual_displacement").
void add_vtk_fields(std::vector<VtkPart>& parts, const Interface& values,
                    const std::string& prefix);

class VtkSeries {
 public:
  /// A new series, or, with `continue_after_step` >= 0, the series of an earlier run continued:
  /// its collection's entries up to that step are kept.
  VtkSeries(std::filesystem::path directory, std::string name, int continue_after_step = -1);

  void write_step(int step, double time, const std::vector<VtkPart>& parts);

  const std::filesystem::path& collection() const { return collection_; }
  std::size_t files_written() const { return files_written_; }

 private:
  struct Entry {
    int step;
    double time;
    int part;
    std::string part_name;
    std::string file;  ///< relative to the collection's directory
  };
  void write_collection() const;
  int part_index(const std::string& name);

  std::filesystem::path directory_;
  std::string name_;
  std::filesystem::path collection_;
  std::vector<Entry> entries_;
  std::vector<std::string> part_names_;  ///< part numbers of the collection, in first-seen order
  std::size_t files_written_ = 0;
};

}  // namespace cocopp
