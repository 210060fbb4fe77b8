// The overlap interpolator: face values along a line, transferred so that value x length is
// conserved where the target faces cover the source faces, on faces of unequal lengths that
// partly overlap at the ends of the chains.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "tests/unit/mappers/interpolators/interpolator_test_helpers.hpp"

namespace cocopp {
namespace {

using testing::make_interpolator;
using testing::Random;

/// Equal faces from `start` to `end`.
std::vector<double> equal_bounds(int faces, double start, double end) {
  std::vector<double> bounds;
  for (int i = 0; i <= faces; ++i) bounds.push_back(start + (end - start) * i / faces);
  return bounds;
}

/// Face centres along y (x and z are not mapped), shuffled so that no order is assumed.
Coordinates centres(const std::vector<double>& bounds) {
  const auto n = static_cast<Eigen::Index>(bounds.size()) - 1;
  Coordinates points = Coordinates::Zero(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Index at = (i * 7) % n;  // a permutation, as n is not a multiple of 7 here
    points(at, 0) = 0.75e-3;
    points(at, 1) =
        0.5 * (bounds[static_cast<std::size_t>(i)] + bounds[static_cast<std::size_t>(i + 1)]);
  }
  return points;
}

/// Lengths of the faces whose centres centres() wrote, in the same (shuffled) order.
Eigen::VectorXd lengths(const std::vector<double>& bounds) {
  const auto n = static_cast<Eigen::Index>(bounds.size()) - 1;
  Eigen::VectorXd result(n);
  for (Eigen::Index i = 0; i < n; ++i)
    result((i * 7) % n) =
        bounds[static_cast<std::size_t>(i + 1)] - bounds[static_cast<std::size_t>(i)];
  return result;
}

double total(const RowMatrix& values, const Eigen::VectorXd& length) {
  return values.col(0).dot(length);
}

TEST(OverlapInterpolator, ConservesTheTotalWhereTheTargetCoversTheSource) {
  // A fine equal source (the film: 100 faces on [0, 1.5]) under a coarser target of equal
  // faces (the wire: faces 6.5 times longer) that reaches past both of its ends.
  const auto source_bounds = equal_bounds(100, 0.0, 1.5);
  const auto target_bounds = equal_bounds(25, -0.37, 2.08);
  auto overlap = make_interpolator("type: overlap\ndirections: [y]\n");
  overlap->initialize(centres(source_bounds), centres(target_bounds));
  Random random(3);
  RowMatrix pressure(100, 2);
  for (Eigen::Index i = 0; i < 100; ++i) pressure.row(i) << random(0.0, 1e9), random(-1e7, 1e7);
  const RowMatrix mapped = overlap->map(pressure);
  for (int column = 0; column < 2; ++column) {
    const double source_total = pressure.col(column).dot(lengths(source_bounds));
    const double target_total = mapped.col(column).dot(lengths(target_bounds));
    EXPECT_NEAR(target_total, source_total, 1e-13 * pressure.col(column).cwiseAbs().sum() * 0.015)
        << "column " << column;
  }
  // A linear interpolation of the same values at the target centres misses most of it.
  auto linear = make_interpolator("type: linear\ndirections: [y]\n");
  linear->initialize(centres(source_bounds), centres(target_bounds));
  const double sampled = total(linear->map(pressure), lengths(target_bounds));
  EXPECT_GT(std::abs(sampled / total(pressure, lengths(source_bounds)) - 1.0), 1e-3);
}

TEST(OverlapInterpolator, TargetFacesPastTheSourceGetZeroForThePartOutside) {
  const auto source_bounds = equal_bounds(10, 0.0, 1.0);
  const auto target_bounds = equal_bounds(4, -0.5, 1.5);  // faces of 0.5: two outside
  auto overlap = make_interpolator("type: overlap\ndirections: [y]\n");
  overlap->initialize(centres(source_bounds), centres(target_bounds));
  const RowMatrix ones = RowMatrix::Ones(10, 1);
  const RowMatrix mapped = overlap->map(ones);
  const Coordinates target = centres(target_bounds);
  for (Eigen::Index t = 0; t < 4; ++t) {
    const bool inside = target(t, 1) > 0.0 && target(t, 1) < 1.0;
    EXPECT_NEAR(mapped(t, 0), inside ? 1.0 : 0.0, 1e-14) << "target at y " << target(t, 1);
  }
  EXPECT_EQ(overlap->quality().unmatched, 2);
}

TEST(OverlapInterpolator, PartlyOverlappingFacesLoseAndDoubleNothing) {
  // Two chains of equal faces with random lengths and offsets: the target starts and ends
  // inside source faces. The load each source face passes on is its value times the part of
  // it the target chain covers, computed here from the bounds.
  Random random(11);
  for (int trial = 0; trial < 20; ++trial) {
    const double source_start = random(-0.1, 0.1), source_end = source_start + random(0.8, 1.2);
    const double target_start = random(0.0, 0.3), target_end = random(0.7, 1.4);
    const auto source_bounds = equal_bounds(37, source_start, source_end);
    const auto target_bounds = equal_bounds(11, target_start, target_end);
    auto overlap = make_interpolator("type: overlap\ndirections: [y]\n");
    overlap->initialize(centres(source_bounds), centres(target_bounds));
    RowMatrix values(37, 1);
    for (Eigen::Index i = 0; i < 37; ++i) values(i, 0) = random(1.0, 2.0);
    double passed_on = 0.0;
    const Eigen::VectorXd source_length = lengths(source_bounds);
    const Coordinates source = centres(source_bounds);
    for (Eigen::Index s = 0; s < 37; ++s) {
      const double low = source(s, 1) - 0.5 * source_length(s);
      const double high = source(s, 1) + 0.5 * source_length(s);
      const double covered =
          std::max(0.0, std::min(high, target_end) - std::max(low, target_start));
      passed_on += values(s, 0) * covered;
    }
    EXPECT_NEAR(total(overlap->map(values), lengths(target_bounds)), passed_on, 1e-14)
        << "trial " << trial;
  }
}

TEST(OverlapInterpolator, NeedsOneDirection) {
  auto overlap = make_interpolator("type: overlap\ndirections: [x, y]\n");
  const auto bounds = equal_bounds(4, 0.0, 1.0);
  Coordinates points = centres(bounds);
  points.col(0) = points.col(1);
  try {
    overlap->initialize(points, points);
    FAIL() << "two directions were accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("directions: [y]"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace cocopp
