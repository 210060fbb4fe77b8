// axisymmetric_2d_to_3d / axisymmetric_3d_to_2d: a 2D axisymmetric model (points in the plane
// of the axial and radial directions) and a 3D model of a wedge or of the full revolution.
// Every 2D point (axial a, radial r) is revolved into `points` copies at angles spread over the
// opening, symmetric about the radial direction; the plane of rotation is spanned by the
// radial direction and the third direction. Vectors keep their axial component and turn their
// radial component with the copy (a 2D vector has no circumferential component); going back
// projects each copy's vector on its local radial direction and averages the copies.
#include <algorithm>
#include <cmath>
#include <vector>

#include "mappers/transformers/point_copies.hpp"

namespace cocopp {
namespace {

constexpr double kPi = 3.14159265358979323846;

class Axisymmetric : public PointCopies {
 public:
  Axisymmetric(const Settings& settings, Side side)
      : PointCopies(side),
        axial_(required_direction(settings, "direction_axial")),
        radial_(required_direction(settings, "direction_radial")),
        third_(3 - axial_ - radial_) {
    if (radial_ == axial_)
      settings.fail("direction_radial", "must differ from direction_axial (both are " +
                                            std::string(direction_name(axial_)) + ")");
    const double angle = settings.get_in_range("angle", 360.0, Range{0.0, 360.0, true, false});
    const bool full = angle >= 360.0;
    // A wedge is usually one cell thick: its points lie on the two faces. The full revolution
    // needs enough copies to resolve the circumference.
    const int points = settings.get_int_in_range("points", full ? 16 : 2, 1);
    angles_ = copy_angles(angle * kPi / 180.0, full, points);
  }

  Coordinates transform_points(const Coordinates& points) override {
    reset(points.rows());
    const double on_axis = 1e-12 * (points.rows() > 0 ? points.cwiseAbs().maxCoeff() : 0.0);
    Coordinates out(points.rows() * static_cast<Eigen::Index>(angles_.size()), 3);
    Eigen::Index j = 0;
    for (Eigen::Index i = 0; i < points.rows(); ++i) {
      // Copies of a point on the axis would coincide, and interpolators reject duplicate
      // points: such a point gets one copy.
      if (std::abs(points(i, radial_)) <= on_axis) {
        add_point(points, i, 0.0, out, j++);
        continue;
      }
      for (double angle : angles_) add_point(points, i, angle, out, j++);
    }
    out.conservativeResize(j, 3);
    return out;
  }

 private:
  /// Row j of `out`: point i revolved by `angle` (rad) from the radial direction.
  void add_point(const Coordinates& points, Eigen::Index i, double angle, Coordinates& out,
                 Eigen::Index j) {
    const double c = std::cos(angle), s = std::sin(angle), r = points(i, radial_);
    out(j, axial_) = points(i, axial_);
    out(j, radial_) = r * c;
    out(j, third_) = r * s;
    add_copy(i, to_copy(c, s));
  }

  /// Angles (rad) of the copies: a wedge from -angle/2 to angle/2 including both faces (one
  /// copy: the centre), the full revolution at equal steps starting at the radial direction.
  static std::vector<double> copy_angles(double angle, bool full, int points) {
    std::vector<double> angles;
    for (int k = 0; k < points; ++k) {
      if (full)
        angles.push_back(2.0 * kPi * k / points);
      else
        angles.push_back(points == 1 ? 0.0 : -angle / 2 + angle * k / (points - 1));
    }
    return angles;
  }

  /// A 2D vector (axial, radial) to a copy at angle (cos c, sin s): the radial unit vector
  /// becomes (c e_radial + s e_third); the third component of the 2D vector is dropped.
  Eigen::Matrix3d to_copy(double c, double s) const {
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    m(axial_, axial_) = 1.0;
    m(radial_, radial_) = c;
    m(third_, radial_) = s;
    return m;
  }

  int axial_, radial_, third_;
  std::vector<double> angles_;
};

struct Axisymmetric2dTo3d : Axisymmetric {
  explicit Axisymmetric2dTo3d(const Settings& s) : Axisymmetric(s, Side::kSource) {}
};
struct Axisymmetric3dTo2d : Axisymmetric {
  explicit Axisymmetric3dTo2d(const Settings& s) : Axisymmetric(s, Side::kTarget) {}
};

}  // namespace

COCOPP_REGISTER(TransformerRegistry, "axisymmetric_2d_to_3d", Axisymmetric2dTo3d)
COCOPP_REGISTER(TransformerRegistry, "axisymmetric_3d_to_2d", Axisymmetric3dTo2d)

}  // namespace cocopp
