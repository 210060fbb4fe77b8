// depth_2d_to_3d / depth_3d_to_2d: a 2D model in a plane and a one-cell-thick 3D mesh of the
// same plane. Every 2D point is copied to each layer of the 3D mesh (its depth coordinates);
// vectors lose their depth component, and going back averages the layers.
#include <algorithm>
#include <vector>

#include "mappers/transformers/point_copies.hpp"

namespace cocopp {
namespace {

class Depth : public PointCopies {
 public:
  Depth(const Settings& settings, Side side)
      : PointCopies(side),
        depth_(required_direction(settings, "direction_depth")),
        layers_(settings.required<std::vector<double>>("coordinates")) {
    if (layers_.empty())
      settings.fail("coordinates", "expected at least one depth coordinate of the 3D mesh");
    auto sorted = layers_;
    std::sort(sorted.begin(), sorted.end());
    // Two layers at one depth would give the interpolator duplicate points.
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      settings.fail("coordinates", "depth coordinates must be distinct");
    projection_ = Eigen::Matrix3d::Identity();
    projection_(depth_, depth_) = 0.0;
  }

  Coordinates transform_points(const Coordinates& points) override {
    const auto layers = static_cast<Eigen::Index>(layers_.size());
    reset(points.rows());
    Coordinates out(points.rows() * layers, 3);
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
      for (Eigen::Index k = 0; k < layers; ++k) {
        out.row(i * layers + k) = points.row(i);
        out(i * layers + k, depth_) = layers_[static_cast<std::size_t>(k)];
        add_copy(i, projection_);
      }
    }
    return out;
  }

 private:
  int depth_;
  std::vector<double> layers_;
  Eigen::Matrix3d projection_;  ///< drops the depth component
};

struct Depth2dTo3d : Depth {
  explicit Depth2dTo3d(const Settings& s) : Depth(s, Side::kSource) {}
};
struct Depth3dTo2d : Depth {
  explicit Depth3dTo2d(const Settings& s) : Depth(s, Side::kTarget) {}
};

}  // namespace

COCOPP_REGISTER(TransformerRegistry, "depth_2d_to_3d", Depth2dTo3d)
COCOPP_REGISTER(TransformerRegistry, "depth_3d_to_2d", Depth3dTo2d)

}  // namespace cocopp
