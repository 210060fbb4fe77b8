#pragma once
// Reading a results file back (ResultsWriter's layout, docs/results.md): what cocopp bench
// compares, what the tests check, and a file a run is still writing (what it has flushed).
// Every HDF5 call is checked: a missing file, dataset or attribute is an error naming the file
// and the object, never a silent zero.
#include <cstddef>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "coupler/results/hdf5_support.hpp"

namespace cocopp {

class ResultsReader {
 public:
  using Shape = std::vector<std::size_t>;
  /// A dataset's values in C order, converted to double, and its shape.
  struct Array {
    Shape shape;
    std::vector<double> values;
    /// Values per row of the first dimension (per time step for the per-step datasets).
    std::size_t row_size() const;
  };

  /// Opens `file` read-only; throws std::runtime_error naming it if it cannot be read.
  explicit ResultsReader(const std::filesystem::path& file);

  const std::filesystem::path& path() const { return path_; }

  // Any object, by its path in the file ("steps/iterations", "x/wall/displacement"; "/" is the
  // root for attributes).
  bool has(const std::string& object) const;
  bool has_attribute(const std::string& object, const std::string& name) const;
  /// The names in a group, in HDF5's name order (empty if the group is not there).
  std::vector<std::string> members(const std::string& group) const;
  Array dataset(const std::string& name) const;
  /// The 0/1 values of a boolean dataset (the enum h5py reads as numpy bool).
  std::vector<int> bools(const std::string& name) const;
  std::string string(const std::string& object, const std::string& name) const;
  std::vector<std::string> strings(const std::string& object, const std::string& name) const;
  double number(const std::string& object, const std::string& name) const;
  std::vector<double> numbers(const std::string& object, const std::string& name) const;

  // The layout.
  std::string status() const { return string("/", "status"); }
  double delta_t() const { return number("/", "delta_t"); }
  /// The time steps written so far.
  std::vector<int> steps() const;
  /// One variable of interface "x" or "y", by model part (parts without it are left out).
  std::map<std::string, Array> variable(const std::string& interface,
                                        const std::string& variable) const;

 private:
  /// Throws H5Error for a dataset that is not there.
  H5Handle open_dataset(const std::string& name) const;

  std::filesystem::path path_;
  H5Handle file_;
};

}  // namespace cocopp
