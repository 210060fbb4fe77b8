#pragma once
// State: the memory of a coupled solver that a restarted run needs to continue exactly as the
// uninterrupted run would (predictor history, secant columns, Aitken's factor, scaling
// weights), as a tree of named numeric arrays. Components write their part with save_state()
// and read it back with load_state(); state_file.hpp puts the tree in an HDF5 file, one group
// per node and one dataset per array, so it can also be inspected with h5py.
#include <Eigen/Core>
#include <map>
#include <string>

namespace cocopp {

class State {
 public:
  /// An array and how it is written: 0 scalar, 1 vector, 2 matrix (rows x columns).
  struct Array {
    Eigen::MatrixXd values;
    int rank = 2;
  };

  void set(const std::string& name, double value);
  void set(const std::string& name, const Eigen::VectorXd& values);
  void set(const std::string& name, Eigen::MatrixXd values);
  void set_array(const std::string& name, Array array);

  bool has(const std::string& name) const { return arrays_.count(name) > 0; }
  /// The array `name`; throws std::runtime_error naming the path if it is absent (a state
  /// written by another coupled solver or an older version).
  const Eigen::MatrixXd& matrix(const std::string& name) const;
  Eigen::VectorXd vector(const std::string& name) const;
  double scalar(const std::string& name) const;

  /// The child node `name`, created if absent.
  State& group(const std::string& name);
  /// The child node `name`; throws std::runtime_error if absent.
  const State& group(const std::string& name) const;
  bool has_group(const std::string& name) const { return groups_.count(name) > 0; }

  const std::map<std::string, Array>& arrays() const { return arrays_; }
  const std::map<std::string, State>& groups() const { return groups_; }

  /// "model/v" for messages: set by group().
  const std::string& path() const { return path_; }

 private:
  [[noreturn]] void missing(const std::string& what, const std::string& name) const;

  std::map<std::string, Array> arrays_;
  std::map<std::string, State> groups_;
  std::string path_;
};

}  // namespace cocopp
