// Accuracy of the interpolators: exact reproduction of linear fields, conservation of totals,
// convergence order with refinement.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/unit/mappers/interpolators/interpolator_test_helpers.hpp"

namespace cocopp::testing {
namespace {

constexpr double kRoundOff = 1e-12;

/// Source and target on the z axis (x, y random and ignored by `directions: [z]`).
Coordinates random_on_axis(Eigen::Index n, unsigned seed, double lo, double hi) {
  Random random(seed);
  Coordinates points(n, 3);
  for (Eigen::Index i = 0; i < n; ++i)
    points.row(i) << random(-1, 1), random(-1, 1), random(lo, hi);
  return points;
}

/// Vertices of a quarter-circle polyline in the x-y plane, and targets on its chords.
Coordinates arc_vertices(int n) {
  Coordinates points(n, 3);
  for (int i = 0; i < n; ++i) {
    const double angle = 0.5 * kPi * i / (n - 1);
    points.row(i) << 2.0 * std::cos(angle), 2.0 * std::sin(angle), 0.0;
  }
  return points;
}
Coordinates points_on_chords(const Coordinates& vertices, unsigned seed) {
  Random random(seed);
  Coordinates points(vertices.rows() - 1, 3);
  for (Eigen::Index i = 0; i + 1 < vertices.rows(); ++i) {
    const double t = random(0.0, 1.0);
    points.row(i) = (1.0 - t) * vertices.row(i) + t * vertices.row(i + 1);
  }
  return points;
}

/// Random points on the tilted plane z = 0.3 x + 0.2 y over the square [lo, hi)^2.
Coordinates random_on_plane(Eigen::Index n, unsigned seed, double lo, double hi) {
  Random random(seed);
  Coordinates points(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double x = random(lo, hi), y = random(lo, hi);
    points.row(i) << x, y, 0.3 * x + 0.2 * y;
  }
  return points;
}

/// Linear fields of z only (for the 1D mappings, where x and y are ignored).
RowMatrix linear_in_z(const Coordinates& x) {
  RowMatrix values(x.rows(), 2);
  values.col(0) = 1.0 + 3.0 * x.col(2).array();
  values.col(1) = -2.0 * x.col(2);
  return values;
}

// --- linear fields are reproduced -------------------------------------------------------------

TEST(LinearInterpolator, ReproducesLinearFieldsIn1D) {
  auto mapper = make_interpolator("type: linear\ndirections: [z]");
  const Coordinates source = random_on_axis(60, 1, 0.0, 1.0);
  const Coordinates target = random_on_axis(80, 2, 0.01, 0.99);
  Coordinates source_with_ends = source;
  source_with_ends(0, 2) = 0.0, source_with_ends(1, 2) = 1.0;
  mapper->initialize(source_with_ends, target);
  EXPECT_LT(relative_error(mapper->map(linear_in_z(source_with_ends)), linear_in_z(target)),
            kRoundOff);
  EXPECT_EQ(mapper->quality().fallbacks, 0);
  EXPECT_NEAR(mapper->quality().max_distance, 0.0, 1e-15);
}

TEST(LinearInterpolator, ReproducesLinearFieldsOnSegmentsIn2D) {
  auto mapper = make_interpolator("type: linear\ndirections: [x, y]");
  const Coordinates source = arc_vertices(40);
  const Coordinates target = points_on_chords(source, 3);
  mapper->initialize(source, target);
  EXPECT_LT(relative_error(mapper->map(linear_field(source)), linear_field(target)), kRoundOff);
  EXPECT_EQ(mapper->quality().fallbacks, 0);
  EXPECT_LT(mapper->quality().max_distance, 1e-12);
}

TEST(LinearInterpolator, ReproducesLinearFieldsOnAPlaneIn3D) {
  auto mapper = make_interpolator("type: linear");
  Coordinates source = random_on_plane(400, 4, 0.0, 1.0);
  source.topRows(4) << 0, 0, 0, 1, 0, 0.3, 0, 1, 0.2, 1, 1, 0.5;  // the corners
  const Coordinates target = random_on_plane(300, 5, 0.05, 0.95);
  mapper->initialize(source, target);
  EXPECT_LT(relative_error(mapper->map(linear_field(source)), linear_field(target)), kRoundOff);
  EXPECT_EQ(mapper->quality().fallbacks, 0);
  EXPECT_LT(mapper->quality().max_distance, 1e-12);
}

TEST(RadialBasisInterpolator, ReproducesLinearFieldsIn1D) {
  auto mapper = make_interpolator("type: radial_basis\ndirections: [z]\nsupport_radius: 0.1");
  const Coordinates source = random_on_axis(100, 6, 0.0, 1.0);
  const Coordinates target = random_on_axis(70, 7, 0.0, 1.0);
  mapper->initialize(source, target);
  EXPECT_LT(relative_error(mapper->map(linear_in_z(source)), linear_in_z(target)), kRoundOff);
}

TEST(RadialBasisInterpolator, ReproducesLinearFieldsOnACurveIn2D) {
  auto mapper = make_interpolator("type: radial_basis\ndirections: [x, y]\nsupport_radius: 0.3");
  const Coordinates source = arc_vertices(40);
  Coordinates target = points_on_chords(source, 8);
  target.col(0) *= 1.01;  // off the curve too: the polynomial part is exact everywhere
  mapper->initialize(source, target);
  EXPECT_LT(relative_error(mapper->map(linear_field(source)), linear_field(target)), kRoundOff);
}

TEST(RadialBasisInterpolator, ReproducesLinearFieldsOnACylinderIn3D) {
  auto mapper = make_interpolator("type: radial_basis\nsupport_radius: 0.5");
  const Coordinates source = random_on_cylinder(600, 9);
  const Coordinates target = random_on_cylinder(500, 10);
  mapper->initialize(source, target);
  EXPECT_LT(relative_error(mapper->map(linear_field(source)), linear_field(target)), kRoundOff);
}

TEST(RadialBasisInterpolator, ReproducesLinearFieldsOnAPlaneIn3D) {
  // The points span only two directions: the polynomial uses those two (no singular system).
  auto mapper = make_interpolator("type: radial_basis\nsupport_radius: 0.25");
  const Coordinates source = random_on_plane(300, 11, 0.0, 1.0);
  const Coordinates target = random_on_plane(200, 12, 0.0, 1.0);
  mapper->initialize(source, target);
  EXPECT_LT(relative_error(mapper->map(linear_field(source)), linear_field(target)), kRoundOff);
}

TEST(RadialBasisInterpolator, WithoutPolynomialInterpolatesAtSourcePoints) {
  auto mapper = make_interpolator("type: radial_basis\nsupport_radius: 0.5\npolynomial: false");
  const Coordinates source = random_on_cylinder(300, 13);
  mapper->initialize(source, source);
  EXPECT_LT(relative_error(mapper->map(linear_field(source)), linear_field(source)), 1e-10);
}

TEST(NearestInterpolator, ReproducesConstantFields) {
  auto mapper = make_interpolator("type: nearest");
  const Coordinates source = random_on_cylinder(200, 14);
  const Coordinates target = random_on_cylinder(300, 15);
  mapper->initialize(source, target);
  RowMatrix constant = RowMatrix::Constant(source.rows(), 3, 2.5);
  EXPECT_EQ(mapper->map(constant), RowMatrix::Constant(target.rows(), 3, 2.5));
}

// --- conservative mapping ---------------------------------------------------------------------

class Conservative : public ::testing::TestWithParam<std::string> {};

TEST_P(Conservative, PreservesTheTotalForce) {
  auto mapper = make_interpolator(GetParam());
  const Coordinates source = random_on_cylinder(500, 16);
  const Coordinates target = random_on_cylinder(700, 17);
  mapper->initialize(source, target);
  Random random(18);
  RowMatrix forces(target.rows(), 3);
  for (Eigen::Index i = 0; i < forces.size(); ++i) forces.data()[i] = random(-1.0, 1.0);
  const RowMatrix mapped = mapper->map_transpose(forces);
  ASSERT_EQ(mapped.rows(), source.rows());
  const Eigen::RowVector3d total = forces.colwise().sum();
  const Eigen::RowVector3d mapped_total = mapped.colwise().sum();
  EXPECT_LT((mapped_total - total).cwiseAbs().maxCoeff(), 1e-12 * forces.cwiseAbs().sum());
  // It is the transpose of map(): <g, M f> = <M^T g, f>.
  const RowMatrix values = linear_field(source);
  EXPECT_NEAR((forces.cwiseProduct(mapper->map(values))).sum(), (mapped.cwiseProduct(values)).sum(),
              1e-10 * forces.cwiseAbs().sum());
}

INSTANTIATE_TEST_SUITE_P(Interpolators, Conservative,
                         ::testing::Values("type: nearest", "type: linear",
                                           "type: radial_basis\nsupport_radius: 0.5"));

// --- convergence with refinement --------------------------------------------------------------

double smooth(double x, double y, double z) {
  return std::sin(2.0 * z) * (1.0 + 0.5 * x * y);
}

RowMatrix smooth_field(const Coordinates& x) {
  RowMatrix values(x.rows(), 1);
  for (Eigen::Index i = 0; i < x.rows(); ++i) values(i, 0) = smooth(x(i, 0), x(i, 1), x(i, 2));
  return values;
}

double max_error(const std::string& yaml, const Coordinates& source, const Coordinates& target) {
  auto mapper = make_interpolator(yaml);
  mapper->initialize(source, target);
  return (mapper->map(smooth_field(source)) - smooth_field(target)).cwiseAbs().maxCoeff();
}

/// Observed order from errors at spacings h and h/2.
double order(double coarse_error, double fine_error) {
  return std::log2(coarse_error / fine_error);
}

Coordinates uniform_on_axis(int n) {
  Coordinates points = Coordinates::Zero(n, 3);
  for (int i = 0; i < n; ++i) points(i, 2) = 2.0 * i / (n - 1);
  return points;
}

/// Random points on the z axis itself (the smooth field depends on x and y too).
Coordinates random_on_z_axis(Eigen::Index n, unsigned seed) {
  Coordinates points = random_on_axis(n, seed, 0.0, 2.0);
  points.leftCols(2).setZero();
  return points;
}

TEST(Convergence, LinearIsSecondOrderIn1D) {
  const Coordinates target = random_on_z_axis(500, 19);
  const std::string yaml = "type: linear\ndirections: [z]";
  const double measured = order(max_error(yaml, uniform_on_axis(41), target),
                                max_error(yaml, uniform_on_axis(81), target));
  EXPECT_GE(measured, 1.8);
  EXPECT_LE(measured, 2.2);
}

TEST(Convergence, NearestIsFirstOrderIn1D) {
  const Coordinates target = random_on_z_axis(500, 20);
  const std::string yaml = "type: nearest\ndirections: [z]";
  const double measured = order(max_error(yaml, uniform_on_axis(41), target),
                                max_error(yaml, uniform_on_axis(81), target));
  EXPECT_GE(measured, 0.8);
  EXPECT_LE(measured, 1.2);
}

TEST(Convergence, LinearIsSecondOrderOnACylinder) {
  // Structured source grids (h and h/2), a fixed shifted target grid: the error includes the
  // distance between the cylinder and the facets, also O(h^2).
  const Coordinates target = grid_on_cylinder(97, 61, 1.0, 2.0, 0.0123);
  const std::string yaml = "type: linear";
  const double coarse = max_error(yaml, grid_on_cylinder(32, 21), target);
  const double fine = max_error(yaml, grid_on_cylinder(64, 41), target);
  const double measured = order(coarse, fine);
  EXPECT_GE(measured, 1.8) << coarse << " " << fine;
  EXPECT_LE(measured, 2.2) << coarse << " " << fine;
}

TEST(Convergence, NearestIsFirstOrderOnACylinder) {
  const Coordinates target = grid_on_cylinder(97, 61, 1.0, 2.0, 0.0123);
  const std::string yaml = "type: nearest";
  const double measured = order(max_error(yaml, grid_on_cylinder(32, 21), target),
                                max_error(yaml, grid_on_cylinder(64, 41), target));
  EXPECT_GE(measured, 0.8);
  EXPECT_LE(measured, 1.2);
}

}  // namespace
}  // namespace cocopp::testing
