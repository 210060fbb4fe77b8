#pragma once
// An interface: model parts, each carrying a list of variables, with all values flattened into
// one Eigen vector, which is what the coupling algorithms work on.
//
// Layout of data(): for each part in order, for each of its variables in order, the values of
// that variable point by point, components contiguous (n_points x components, row-major).
// The solver protocol sends exactly this vector.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "core/data/model_part.hpp"

namespace cocopp {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

class Interface {
 public:
  struct Part {
    std::shared_ptr<const ModelPart> model_part;
    std::vector<std::string> variables;
  };
  /// One (model part, variable) block of data().
  struct Block {
    std::string model_part;
    std::string variable;
    Eigen::Index offset;
    Eigen::Index points;
    int components;
  };

  Interface() = default;
  /// Throws std::invalid_argument for an unknown variable or a repeated model part.
  explicit Interface(std::vector<Part> parts);

  const std::vector<Part>& parts() const { return parts_; }
  const std::vector<Block>& blocks() const { return blocks_; }
  Eigen::Index size() const { return data_.size(); }

  const Eigen::VectorXd& data() const { return data_; }
  /// Replace all values; throws std::invalid_argument if the size differs.
  void set_data(const Eigen::VectorXd& values);

  /// The block of `variable` on `model_part`; throws std::out_of_range if absent.
  const Block& block(const std::string& model_part, const std::string& variable) const;
  /// Values of one variable on one model part as an n_points x components matrix view.
  Eigen::Map<RowMatrix> values(const std::string& model_part, const std::string& variable);
  Eigen::Map<const RowMatrix> values(const std::string& model_part,
                                     const std::string& variable) const;

  /// Same model parts (names and point counts) and variables, in the same order.
  bool same_layout(const Interface& other) const;
  /// "wall: displacement (100 x 3)"; one entry per block, separated by "; ".
  std::string describe() const;

 private:
  std::vector<Part> parts_;
  std::vector<Block> blocks_;
  Eigen::VectorXd data_;
};

}  // namespace cocopp
