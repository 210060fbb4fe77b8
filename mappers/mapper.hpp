#pragma once
// Mapper: the mapping of one case-file entry between two model parts: an interpolator with
// optional transformers on either side, consistent or conservative, and a mask of the vector
// components to pass. In a case file:
//
//   input_mapper:
//     type: linear          # the interpolator (docs/mappers-interpolators.md)
//     directions: [z]
//     transformers: []      # e.g. [{type: axisymmetric_2d_to_3d}] (docs/mappers-transformers.md)
//     conservative: false   # true: M^T for every variable, totals preserved (nodal forces);
//                           # a list ([force]): M^T for those, the others consistent
//     conservative_scale: 1 # factor on what is mapped conservatively: the target's share of
//                           # the source's body (a 1 degree sector under a 5 degree wedge: 0.2)
//     components: [x, y, z] # vector components passed on; the others become 0
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "mappers/interpolators/interpolator.hpp"
#include "mappers/transformers/transformer.hpp"

namespace cocopp {

class Mapper {
 public:
  explicit Mapper(const Settings& settings);

  /// Build the mapping from `source` to `target` points (rows x y z).
  void initialize(const Coordinates& source, const Coordinates& target);
  /// Values of one variable at the source points (n x 1 or n x 3) at the target points:
  /// conservatively if the mapper is conservative for every variable (`conservative: true`).
  RowMatrix map(const RowMatrix& source_values) const;
  /// The same for the named variable: conservatively if the mapper is for every variable or
  /// lists it (`conservative: [force]`).
  RowMatrix map(const RowMatrix& source_values, const std::string& variable) const;

  /// The quality of the consistent mapping (of the conservative one if there is no other).
  const MappingQuality& quality() const;
  /// Per target point, the distance to the source stencil that the consistent mapping uses
  /// (infinite where the target is unmatched), measured where the interpolator works (after
  /// the transformers) and brought back to the target points (averaged over their copies).
  /// Throws std::invalid_argument for a mapper that maps everything conservatively.
  Eigen::VectorXd target_distances() const;
  bool initialized() const { return initialized_; }

 private:
  bool conservative_for(const std::string& variable) const;
  RowMatrix map_with(const RowMatrix& source_values, bool conservative) const;

  /// Consistent (source -> target) and conservative (built target -> source, applied as
  /// M^T); each only where some variable needs it.
  std::unique_ptr<Interpolator> consistent_, conservative_;
  std::vector<std::unique_ptr<Transformer>> source_side_, target_side_;
  bool all_conservative_ = false;
  std::set<std::string> conservative_variables_;
  double conservative_scale_ = 1.0;
  Eigen::RowVector3d mask_ = Eigen::RowVector3d::Ones();
  bool initialized_ = false;
};

}  // namespace cocopp
