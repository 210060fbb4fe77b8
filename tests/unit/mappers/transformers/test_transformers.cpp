// Transformers: round trips (forward then backward) return the input, transformed geometry is
// where it should be, and every settings error names its key.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "mappers/transformers/transformer.hpp"

using namespace cocopp;

namespace {

std::unique_ptr<Transformer> make(const std::string& yaml) {
  return TransformerRegistry::instance().create(Settings::load_string(yaml, "m.yaml"));
}

/// Points in the x (axial) - y (radial) plane, none on the axis.
Coordinates plane_points() {
  Coordinates points(4, 3);
  points << 0.0, 0.5, 0.0,  //
      0.1, 1.0, 0.0,        //
      0.2, 0.25, 0.0,       //
      -0.3, 2.0, 0.0;
  return points;
}

/// Vectors with no component out of the x-y plane.
RowMatrix plane_vectors() {
  RowMatrix vectors(4, 3);
  vectors << 1.0, -2.0, 0.0,  //
      0.5, 3.0, 0.0,          //
      -1.5, 0.25, 0.0,        //
      2.0, -0.75, 0.0;
  return vectors;
}

RowMatrix scalars() {
  RowMatrix values(4, 1);
  values << 1.0, -2.0, 3.5, 1e5;
  return values;
}

constexpr double kPi = 3.14159265358979323846;

}  // namespace

TEST(Permutation, PermutesPointsAndVectors) {
  auto t = make("type: permutation\npermutation: [2, 0, 1]");
  EXPECT_EQ(t->side(), Transformer::Side::kSource);
  Coordinates points(1, 3);
  points << 1.0, 2.0, 3.0;
  const Coordinates moved = t->transform_points(points);
  EXPECT_EQ(moved(0, 0), 3.0);  // new x = old z
  EXPECT_EQ(moved(0, 1), 1.0);
  EXPECT_EQ(moved(0, 2), 2.0);
  RowMatrix vector(1, 3);
  vector << 4.0, 5.0, 6.0;
  const RowMatrix forward = t->forward(vector);
  EXPECT_EQ(forward(0, 0), 6.0);
  EXPECT_EQ(forward(0, 1), 4.0);
  EXPECT_EQ(forward(0, 2), 5.0);
}

TEST(Permutation, RoundTripIsExact) {
  auto t = make("type: permutation\npermutation: [1, 2, 0]");
  Coordinates points = plane_points();
  points.col(2) << 7.0, -8.0, 9.0, 0.125;
  RowMatrix vectors = plane_vectors();
  vectors.col(2) << 0.3, -0.7, 11.0, 1e-9;
  const Coordinates moved = t->transform_points(points);
  EXPECT_EQ(RowMatrix(t->backward(RowMatrix(moved))), RowMatrix(points));
  EXPECT_EQ(t->backward(t->forward(vectors)), vectors);
  EXPECT_EQ(t->backward(t->forward(scalars())), scalars());
}

TEST(Permutation, ChecksValueShapes) {
  auto t = make("type: permutation\npermutation: [0, 1, 2]");
  t->transform_points(plane_points());
  EXPECT_THROW(t->forward(RowMatrix::Zero(3, 3)), std::invalid_argument);
  EXPECT_THROW(t->forward(RowMatrix::Zero(4, 2)), std::invalid_argument);
}

class AxisymmetricRoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(AxisymmetricRoundTrip, ReturnsTheInput) {
  for (const std::string type : {"axisymmetric_2d_to_3d", "axisymmetric_3d_to_2d"}) {
    auto t = make("type: " + type + "\ndirection_axial: x\ndirection_radial: y\n" + GetParam());
    t->transform_points(plane_points());
    EXPECT_TRUE(t->backward(t->forward(scalars())).isApprox(scalars(), 1e-14)) << type;
    EXPECT_TRUE(t->backward(t->forward(plane_vectors())).isApprox(plane_vectors(), 1e-14)) << type;
  }
}

INSTANTIATE_TEST_SUITE_P(Openings, AxisymmetricRoundTrip,
                         ::testing::Values("angle: 5", "angle: 5\npoints: 3", "angle: 360",
                                           "points: 7", "angle: 90\npoints: 1"));

TEST(Axisymmetric, SidesAndDefaultCopies) {
  auto wedge =
      make("type: axisymmetric_2d_to_3d\ndirection_axial: x\ndirection_radial: y\nangle: 5");
  EXPECT_EQ(wedge->side(), Transformer::Side::kSource);
  EXPECT_EQ(wedge->transform_points(plane_points()).rows(), 4 * 2);
  auto full = make("type: axisymmetric_3d_to_2d\ndirection_axial: x\ndirection_radial: y");
  EXPECT_EQ(full->side(), Transformer::Side::kTarget);
  EXPECT_EQ(full->transform_points(plane_points()).rows(), 4 * 16);
}

TEST(Axisymmetric, PointsLieOnCirclesAboutTheAxis) {
  // Axial z, radial x: the plane of rotation is x-y.
  auto t = make(
      "type: axisymmetric_2d_to_3d\ndirection_axial: z\ndirection_radial: x\nangle: 30\n"
      "points: 4");
  Coordinates points(2, 3);
  points << 0.5, 0.0, 1.0,  //
      2.0, 0.0, -0.5;
  const Coordinates moved = t->transform_points(points);
  ASSERT_EQ(moved.rows(), 8);
  for (Eigen::Index j = 0; j < moved.rows(); ++j) {
    const Eigen::Index i = j / 4;
    EXPECT_DOUBLE_EQ(moved(j, 2), points(i, 2)) << j;
    EXPECT_NEAR(std::hypot(moved(j, 0), moved(j, 1)), points(i, 0), 1e-14) << j;
    EXPECT_LE(std::abs(std::atan2(moved(j, 1), moved(j, 0))), 15.0 * kPi / 180.0 + 1e-12);
  }
  // The wedge is symmetric about the radial direction, faces included.
  EXPECT_NEAR(std::atan2(moved(0, 1), moved(0, 0)), -15.0 * kPi / 180.0, 1e-14);
  EXPECT_NEAR(std::atan2(moved(3, 1), moved(3, 0)), 15.0 * kPi / 180.0, 1e-14);
}

TEST(Axisymmetric, RadialVectorsTurnWithTheirCopy) {
  auto t = make(
      "type: axisymmetric_2d_to_3d\ndirection_axial: y\ndirection_radial: z\nangle: 360\n"
      "points: 6");
  Coordinates points(1, 3);
  points << 0.0, 0.4, 1.5;
  const Coordinates moved = t->transform_points(points);
  RowMatrix vector(1, 3);
  vector << 0.0, 0.25, 2.0;  // axial 0.25, radial 2
  const RowMatrix out = t->forward(vector);
  ASSERT_EQ(out.rows(), 6);
  for (Eigen::Index j = 0; j < 6; ++j) {
    EXPECT_DOUBLE_EQ(out(j, 1), 0.25);  // axial component kept
    // The rest is radial: along (point - axis), length 2.
    const Eigen::Vector2d radial(moved(j, 2), moved(j, 0));
    const Eigen::Vector2d v(out(j, 2), out(j, 0));
    EXPECT_NEAR(radial.x() * v.y() - radial.y() * v.x(), 0.0, 1e-14) << j;
    EXPECT_GT(radial.dot(v), 0.0) << j;
    EXPECT_NEAR(v.norm(), 2.0, 1e-14) << j;
  }
}

TEST(Axisymmetric, BackwardDropsTheCircumferentialComponent) {
  auto t = make("type: axisymmetric_3d_to_2d\ndirection_axial: x\ndirection_radial: y");
  Coordinates points(1, 3);
  points << 0.0, 1.0, 0.0;
  const Coordinates moved = t->transform_points(points);
  // A swirl: axial 1, radial 3, circumferential 5 at every copy.
  RowMatrix swirl(moved.rows(), 3);
  for (Eigen::Index j = 0; j < moved.rows(); ++j) {
    const double c = moved(j, 1), s = moved(j, 2);  // radius 1
    swirl.row(j) << 1.0, 3.0 * c - 5.0 * s, 3.0 * s + 5.0 * c;
  }
  const RowMatrix back = t->backward(swirl);
  EXPECT_NEAR(back(0, 0), 1.0, 1e-14);
  EXPECT_NEAR(back(0, 1), 3.0, 1e-14);
  EXPECT_EQ(back(0, 2), 0.0);
}

TEST(Axisymmetric, PointOnTheAxisGetsOneCopy) {
  auto t = make("type: axisymmetric_2d_to_3d\ndirection_axial: x\ndirection_radial: y");
  Coordinates points(2, 3);
  points << 0.0, 0.0, 0.0,  //
      0.0, 1.0, 0.0;
  EXPECT_EQ(t->transform_points(points).rows(), 1 + 16);
  RowMatrix values(2, 1);
  values << 4.0, 5.0;
  EXPECT_TRUE(t->backward(t->forward(values)).isApprox(values, 1e-14));
}

TEST(Depth, CopiesToEachLayerAndAveragesBack) {
  for (const std::string type : {"depth_2d_to_3d", "depth_3d_to_2d"}) {
    auto t = make("type: " + type + "\ndirection_depth: z\ncoordinates: [-0.0005, 0.0005]");
    EXPECT_EQ(t->side(),
              type == "depth_2d_to_3d" ? Transformer::Side::kSource : Transformer::Side::kTarget);
    const Coordinates moved = t->transform_points(plane_points());
    ASSERT_EQ(moved.rows(), 8);
    for (Eigen::Index j = 0; j < 8; ++j) {
      EXPECT_EQ(moved.row(j).head<2>(), plane_points().row(j / 2).head<2>());
      EXPECT_EQ(moved(j, 2), j % 2 == 0 ? -0.0005 : 0.0005);
    }
    RowMatrix vectors = plane_vectors();
    const RowMatrix out = t->forward(vectors);
    EXPECT_EQ(out.row(3), vectors.row(1));
    EXPECT_EQ(t->backward(out), vectors);
    EXPECT_EQ(t->backward(t->forward(scalars())), scalars());
    vectors(0, 2) = 9.0;  // a depth component is dropped
    EXPECT_EQ(t->forward(vectors)(0, 2), 0.0);
  }
}

TEST(Depth, BackwardAveragesTheLayers) {
  auto t = make("type: depth_3d_to_2d\ndirection_depth: y\ncoordinates: [0, 1, 2]");
  Coordinates points(1, 3);
  points << 1.0, 0.0, 2.0;
  t->transform_points(points);
  RowMatrix layers(3, 3);
  layers << 1.0, 5.0, 3.0,  //
      2.0, 6.0, 4.0,        //
      3.0, 7.0, 8.0;
  const RowMatrix back = t->backward(layers);
  EXPECT_DOUBLE_EQ(back(0, 0), 2.0);
  EXPECT_EQ(back(0, 1), 0.0);
  EXPECT_DOUBLE_EQ(back(0, 2), 5.0);
}

namespace {

/// The CaseError message of creating a transformer from `yaml` ("" if it succeeds).
std::string error_of(const std::string& yaml) {
  try {
    make(yaml);
  } catch (const CaseError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(TransformerSettings, ErrorsNameTheKey) {
  const std::string axi = "type: axisymmetric_2d_to_3d\n";
  const struct {
    std::string yaml, key;
  } cases[] = {
      {"type: permutation", "permutation"},
      {"type: permutation\npermutation: [0, 1]", "permutation"},
      {"type: permutation\npermutation: [0, 1, 1]", "permutation"},
      {"type: permutation\npermutation: [0, 1, 3]", "permutation"},
      {"type: permutation\npermutation: [0, 1.5, 2]", "permutation"},
      {"type: permutation\npermutation: [x, y, z]", "permutation"},
      {axi + "direction_axial: w\ndirection_radial: y", "direction_axial"},
      {axi + "direction_radial: y", "direction_axial"},
      {axi + "direction_axial: x\ndirection_radial: q", "direction_radial"},
      {axi + "direction_axial: x\ndirection_radial: x", "direction_radial"},
      {axi + "direction_axial: x\ndirection_radial: y\nangle: 0", "angle"},
      {axi + "direction_axial: x\ndirection_radial: y\nangle: 361", "angle"},
      {axi + "direction_axial: x\ndirection_radial: y\nangle: -5", "angle"},
      {axi + "direction_axial: x\ndirection_radial: y\npoints: 0", "points"},
      {"type: depth_2d_to_3d\ndirection_depth: d\ncoordinates: [0, 1]", "direction_depth"},
      {"type: depth_2d_to_3d\ndirection_depth: z", "coordinates"},
      {"type: depth_2d_to_3d\ndirection_depth: z\ncoordinates: []", "coordinates"},
      {"type: depth_2d_to_3d\ndirection_depth: z\ncoordinates: [1, 1]", "coordinates"},
  };
  for (const auto& c : cases) {
    const std::string message = error_of(c.yaml);
    EXPECT_NE(message, "") << c.yaml;
    EXPECT_NE(message.find("'" + c.key + "'"), std::string::npos) << c.yaml << "\n" << message;
  }
}

TEST(TransformerSettings, AllAreRegistered) {
  const auto names = TransformerRegistry::instance().names();
  for (const char* name : {"permutation", "axisymmetric_2d_to_3d", "axisymmetric_3d_to_2d",
                           "depth_2d_to_3d", "depth_3d_to_2d"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
}
