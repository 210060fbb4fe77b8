#pragma once
// Mapper: the mapping of one case-file entry between two model parts: an interpolator with
// optional transformers on either side, consistent or conservative, and a mask of the vector
// components to pass. In a case file:
//
//   input_mapper:
//     type: linear          # the interpolator (docs/mappers-interpolators.md)
//     directions: [z]
//     transformers: []      # e.g. [{type: axisymmetric_2d_to_3d}] (docs/mappers-transformers.md)
//     conservative: false   # true: M^T, totals preserved (nodal forces)
//     components: [x, y, z] # vector components passed on; the others become 0
#include <memory>
#include <vector>

#include "mappers/interpolators/interpolator.hpp"
#include "mappers/transformers/transformer.hpp"

namespace cocopp {

class Mapper {
 public:
  explicit Mapper(const Settings& settings);

  /// Build the mapping from `source` to `target` points (rows x y z).
  void initialize(const Coordinates& source, const Coordinates& target);
  /// Values of one variable at the source points (n x 1 or n x 3) at the target points.
  RowMatrix map(const RowMatrix& source_values) const;

  const MappingQuality& quality() const { return interpolator_->quality(); }
  bool initialized() const { return initialized_; }

 private:
  std::unique_ptr<Interpolator> interpolator_;
  std::vector<std::unique_ptr<Transformer>> source_side_, target_side_;
  bool conservative_;
  Eigen::RowVector3d mask_ = Eigen::RowVector3d::Ones();
  bool initialized_ = false;
};

}  // namespace cocopp
