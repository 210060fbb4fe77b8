#pragma once
// Transformers change the geometry of one side of a mapping so that an interpolator can work
// between sides that do not live in the same space: swapped axes, a 2D axisymmetric model and a
// 3D wedge, a 2D model and a one-cell-thick 3D mesh.
//
// A transformer stands on the source side (it turns the source points and values into points
// and values the interpolator takes: `forward`) or on the target side (the interpolator maps
// onto the transformed target points, `backward` brings the values back to the real target
// points, averaging where several transformed points stand for one real point).
#include <Eigen/Core>

#include "core/case/registry.hpp"
#include "core/data/interface.hpp"
#include "core/data/model_part.hpp"

namespace cocopp {

class Transformer {
 public:
  static constexpr const char* kind = "transformer";
  enum class Side { kSource, kTarget };
  virtual ~Transformer() = default;

  /// Which side of the interpolator this transformer stands on.
  virtual Side side() const = 0;
  /// The points the interpolator sees for the given points of this side (remembered for the
  /// value transforms that follow).
  virtual Coordinates transform_points(const Coordinates& points) = 0;
  /// Values of this side (n x components, components 1 for scalars, 3 for vectors) at the
  /// transformed points.
  virtual RowMatrix forward(const RowMatrix& values) const = 0;
  /// Values at the transformed points back at this side's points.
  virtual RowMatrix backward(const RowMatrix& values) const = 0;
  /// Whether totals survive the transform (each point one transformed point, vectors turned
  /// but not stretched): only then can a conservative mapping pass through it. Copies that
  /// stand for one point (a wedge's sides) would count a force once per copy.
  virtual bool keeps_totals() const { return false; }
};

using TransformerRegistry = Registry<Transformer>;

}  // namespace cocopp
