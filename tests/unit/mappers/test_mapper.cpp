// The Mapper's choice per variable: a face force (a total, N) mapped conservatively beside
// pressures mapped as means, through a permutation of the axes, scaled from the source's
// sector to the target's; and the case-file errors of that choice.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

#include "core/case/settings.hpp"
#include "mappers/mapper.hpp"

namespace cocopp {
namespace {

constexpr const char* kFilmToWire =
    "type: overlap\n"
    "directions: [y]\n"
    "conservative: [force]\n"
    "conservative_scale: 0.2\n"
    "transformers:\n"
    "  - {type: permutation, permutation: [1, 2, 0]}\n";

/// Face centres along an axis: a film's (x across its wedge, y its radius, z its axis), a
/// wire's (x its radius, y its axis).
Coordinates film_faces(int n, double length) {
  Coordinates points = Coordinates::Zero(n, 3);
  for (int i = 0; i < n; ++i) {
    points(i, 1) = 0.75e-3;
    points(i, 2) = (i + 0.5) * length / n;
  }
  return points;
}

Coordinates wire_faces(int n, double start, double end) {
  Coordinates points = Coordinates::Zero(n, 3);
  for (int i = 0; i < n; ++i) {
    points(i, 0) = 0.75e-3;
    points(i, 1) = start + (i + 0.5) * (end - start) / n;
  }
  return points;
}

TEST(Mapper, AListedVariableKeepsItsTotalTheOthersTheirMean) {
  Mapper mapper(Settings::load_string(kFilmToWire, "case.yaml"));
  // 120 film faces on [0, 1.5 mm] under 23 wire faces on [-0.4, 2.1 mm]: none aligned.
  const Coordinates film = film_faces(120, 1.5e-3), wire = wire_faces(23, -0.4e-3, 2.1e-3);
  mapper.initialize(film, wire);
  RowMatrix force(film.rows(), 3), pressure(film.rows(), 1);
  for (Eigen::Index i = 0; i < film.rows(); ++i) {
    const double z = film(i, 2);
    force.row(i) << 0.0, -3.0 - 1e3 * z, 0.2 + 50.0 * z;  // film (across, radial, axial)
    pressure(i, 0) = 7e6;
  }
  const RowMatrix on_wire = mapper.map(force, "force");
  ASSERT_EQ(on_wire.rows(), wire.rows());
  const Eigen::RowVector3d film_total = force.colwise().sum();
  const Eigen::RowVector3d wire_total = on_wire.colwise().sum();
  // Permuted (film radial -> wire x, film axial -> wire y) and scaled to the wire's sector.
  EXPECT_NEAR(wire_total(0), 0.2 * film_total(1), 1e-13 * std::abs(film_total(1)));
  EXPECT_NEAR(wire_total(1), 0.2 * film_total(2), 1e-13 * std::abs(film_total(1)));
  EXPECT_EQ(wire_total(2), 0.0);
  // A mean: a constant pressure stays constant where the film covers a wire face whole.
  const RowMatrix mean = mapper.map(pressure, "pressure");
  for (Eigen::Index t = 0; t < wire.rows(); ++t)
    if (wire(t, 1) - 0.055e-3 > 0.0 && wire(t, 1) + 0.055e-3 < 1.5e-3) {
      EXPECT_NEAR(mean(t, 0), 7e6, 1e-6) << "wire face " << t;
    }
  // Without a variable's name, a mapper conservative for some variables maps consistently.
  EXPECT_EQ(mapper.map(pressure), mean);
}

TEST(Mapper, ConservativeForEveryVariableAsBefore) {
  Mapper mapper(
      Settings::load_string("type: overlap\ndirections: [y]\nconservative: true\n"
                            "transformers: [{type: permutation, permutation: [1, 2, 0]}]",
                            "case.yaml"));
  const Coordinates film = film_faces(40, 1.0), wire = wire_faces(7, -0.1, 1.2);
  mapper.initialize(film, wire);
  const RowMatrix ones = RowMatrix::Ones(film.rows(), 1);
  EXPECT_NEAR(mapper.map(ones).sum(), 40.0, 1e-12);
  EXPECT_NEAR(mapper.map(ones, "pressure").sum(), 40.0, 1e-12);
}

void expect_case_error(const std::string& yaml, const std::string& part) {
  try {
    Mapper mapper(Settings::load_string(yaml, "case.yaml"));
    FAIL() << "no error for:\n" << yaml;
  } catch (const std::exception& error) {
    EXPECT_NE(std::string(error.what()).find(part), std::string::npos) << error.what();
    EXPECT_NE(std::string(error.what()).find("case.yaml:"), std::string::npos) << error.what();
  }
}

TEST(Mapper, CaseErrorsOfTheConservativeChoiceSayWhatToChange) {
  expect_case_error("type: overlap\ndirections: [y]\nconservative: [forse]\n",
                    "did you mean 'force'");
  expect_case_error("type: overlap\ndirections: [y]\nconservative_scale: 0.2\n",
                    "nothing is: give `conservative`");
  expect_case_error(
      "type: overlap\ndirections: [y]\nconservative: [force]\n"
      "conservative_scale: 0\n",
      "must be positive");
  expect_case_error(
      "type: linear\nconservative: [force]\n"
      "transformers: [{type: axisymmetric_2d_to_3d, direction_axial: y, "
      "direction_radial: x, angle: 5.0}]\n",
      "only one that keeps each point one point");
}

/// Points along z at the given positions.
Coordinates on_axis(const std::vector<double>& z) {
  Coordinates points = Coordinates::Zero(static_cast<Eigen::Index>(z.size()), 3);
  for (std::size_t i = 0; i < z.size(); ++i) points(static_cast<Eigen::Index>(i), 2) = z[i];
  return points;
}

// What a solver group decides ownership by: 0 where the target lies within the source's
// stencils, the distance to the nearest source point beyond its ends, infinite where the
// target is unmatched; through a depth transformer, per real target point.
TEST(Mapper, TargetDistancesSayHowFarEachTargetIsFromTheSource) {
  Mapper linear{Settings::load_string("{type: linear, directions: [z]}", "test")};
  linear.initialize(on_axis({0.0, 1.0, 2.0}), on_axis({0.5, 2.0, 2.25, 3.0, -1.0}));
  const Eigen::VectorXd d = linear.target_distances();
  ASSERT_EQ(d.size(), 5);
  EXPECT_DOUBLE_EQ(d(0), 0.0);
  EXPECT_DOUBLE_EQ(d(1), 0.0);
  EXPECT_DOUBLE_EQ(d(2), 0.25);
  EXPECT_DOUBLE_EQ(d(3), 1.0);
  EXPECT_DOUBLE_EQ(d(4), 1.0);

  Mapper limited{Settings::load_string(
      "{type: nearest, directions: [z], max_distance: 0.5, unmatched: zero}", "test")};
  limited.initialize(on_axis({0.0, 1.0}), on_axis({1.25, 2.0}));
  EXPECT_DOUBLE_EQ(limited.target_distances()(0), 0.25);
  EXPECT_TRUE(std::isinf(limited.target_distances()(1)));

  Mapper conservative{Settings::load_string("{type: nearest, conservative: true}", "test")};
  conservative.initialize(on_axis({0.0, 1.0}), on_axis({0.0, 1.0}));
  EXPECT_THROW(conservative.target_distances(), std::invalid_argument);
}

TEST(Mapper, TargetDistancesComeBackThroughATargetSideTransformer) {
  // A 2D target seen as two depth layers of a 3D source: the distance per real target point.
  Mapper mapper{Settings::load_string(
      "{type: nearest, transformers: [{type: depth_3d_to_2d, direction_depth: x, "
      "coordinates: [-1.0, 1.0]}]}",
      "test")};
  mapper.initialize(on_axis({0.0, 1.0}), on_axis({0.0, 3.0}));
  const Eigen::VectorXd d = mapper.target_distances();
  ASSERT_EQ(d.size(), 2);
  EXPECT_NEAR(d(0), 1.0, 1e-12);             // the layers at x = -1, 1 lie 1 from (0, 0, 0)
  EXPECT_NEAR(d(1), std::sqrt(5.0), 1e-12);  // (+-1, 0, 3) from (0, 0, 1)
}

}  // namespace
}  // namespace cocopp
