// Settings, checks on the point sets, unmatched targets and the quality report.
#include <gtest/gtest.h>

#include <stdexcept>

#include "tests/unit/mappers/interpolators/interpolator_test_helpers.hpp"

namespace cocopp::testing {
namespace {

/// EXPECT that `statement` throws `Exception` with a message containing `part`.
template <class Exception, class Statement>
void expect_error(Statement statement, const std::string& part) {
  try {
    statement();
    ADD_FAILURE() << "no exception; expected one containing: " << part;
  } catch (const Exception& error) {
    EXPECT_NE(std::string(error.what()).find(part), std::string::npos) << error.what();
  }
}

Coordinates points(std::initializer_list<std::array<double, 3>> rows) {
  Coordinates result(static_cast<Eigen::Index>(rows.size()), 3);
  Eigen::Index i = 0;
  for (const auto& row : rows) result.row(i++) << row[0], row[1], row[2];
  return result;
}

// --- settings ---------------------------------------------------------------------------------

TEST(InterpolatorSettings, RejectsUnknownDirectionsWithASuggestion) {
  expect_error<CaseError>([] { make_interpolator("type: linear\ndirections: [x, Y]"); },
                          "did you mean 'y'?");
  expect_error<CaseError>([] { make_interpolator("type: linear\ndirections: [w]"); },
                          "'w' is not one of: x, y, z");
  expect_error<CaseError>([] { make_interpolator("type: linear\ndirections: [x, x]"); },
                          "'x' is listed twice");
  expect_error<CaseError>([] { make_interpolator("type: linear\ndirections: []"); },
                          "at least one");
}

TEST(InterpolatorSettings, ChecksMaxDistanceAndUnmatched) {
  expect_error<CaseError>([] { make_interpolator("type: nearest\nmax_distance: 0"); }, "> 0");
  expect_error<CaseError>([] { make_interpolator("type: nearest\nunmatched: nearst"); },
                          "did you mean 'nearest'?");
  expect_error<CaseError>([] { make_interpolator("type: radial_basis"); }, "support_radius");
}

TEST(InterpolatorSettings, AllKeysAreRead) {
  const auto settings = Settings::load_string(
      "type: radial_basis\ndirections: [x, z]\nmax_distance: 1\nunmatched: error\n"
      "support_radius: 0.5\npolynomial: false",
      "m.yaml");
  InterpolatorRegistry::instance().create(settings);
  EXPECT_NO_THROW(settings.check_unused_keys());
}

// --- checks on the point sets -----------------------------------------------------------------

TEST(InterpolatorChecks, RejectsEmptySets) {
  auto mapper = make_interpolator("type: nearest");
  const Coordinates some = points({{0, 0, 0}, {1, 0, 0}});
  expect_error<std::invalid_argument>([&] { mapper->initialize(Coordinates(0, 3), some); },
                                      "source point set is empty");
  expect_error<std::invalid_argument>([&] { mapper->initialize(some, Coordinates(0, 3)); },
                                      "target point set is empty");
}

TEST(InterpolatorChecks, NamesDuplicatePoints) {
  auto mapper = make_interpolator("type: linear");
  const Coordinates unique = points({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const Coordinates repeated = points({{0, 0, 0}, {1, 0, 0}, {0.5, 0.5, 0}, {1, 0, 0}});
  expect_error<std::invalid_argument>([&] { mapper->initialize(repeated, unique); },
                                      "source points 1 (1, 0, 0) and 3 (1, 0, 0) coincide");
  expect_error<std::invalid_argument>([&] { mapper->initialize(unique, repeated); },
                                      "target points 1 (1, 0, 0) and 3 (1, 0, 0) coincide");
}

TEST(InterpolatorChecks, DuplicatesAreJudgedInTheSelectedDirections) {
  // Distinct in 3D, but the same z: a z-only mapping cannot tell them apart.
  auto mapper = make_interpolator("type: linear\ndirections: [z]");
  const Coordinates source = points({{0, 0, 0}, {1, 0, 1}, {0, 1, 1}});
  expect_error<std::invalid_argument>([&] { mapper->initialize(source, source); },
                                      "in the mapped directions (z)");
}

TEST(InterpolatorChecks, RejectsBoundingBoxesThatDoNotOverlap) {
  auto mapper = make_interpolator("type: nearest");
  const Coordinates source = points({{0, 0, 0}, {1, 1, 0}});
  const Coordinates shifted = points({{0, 0, 5}, {1, 1, 5}});
  expect_error<std::invalid_argument>([&] { mapper->initialize(source, shifted); },
                                      "do not overlap in direction z");
  // Within the tolerance: fine.
  const Coordinates touching = points({{0, 0, 1e-9}, {1, 1, 1e-9}});
  EXPECT_NO_THROW(mapper->initialize(source, touching));
}

TEST(InterpolatorChecks, MapChecksRowCounts) {
  auto mapper = make_interpolator("type: nearest");
  const Coordinates source = points({{0, 0, 0}, {1, 0, 0}});
  expect_error<std::logic_error>([&] { mapper->map(RowMatrix::Zero(2, 1)); }, "before");
  mapper->initialize(source, points({{0.2, 0, 0}}));
  expect_error<std::invalid_argument>([&] { mapper->map(RowMatrix::Zero(3, 1)); },
                                      "values for 3 points, but the source has 2");
  expect_error<std::invalid_argument>([&] { mapper->map_transpose(RowMatrix::Zero(2, 1)); },
                                      "values for 2 points, but the target has 1");
}

TEST(InterpolatorChecks, RadialBasisSupportTooSmall) {
  auto mapper = make_interpolator("type: radial_basis\nsupport_radius: 0.1");
  const Coordinates source = points({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0.5}});
  expect_error<std::invalid_argument>([&] { mapper->initialize(source, source); },
                                      "support_radius 0.1 too small: source point 0 (0, 0, 0)");
}

// --- directions -------------------------------------------------------------------------------

TEST(InterpolatorDirections, AZMappingIgnoresXAndY) {
  auto mapper = make_interpolator("type: linear\ndirections: [z]");
  const Coordinates source = points({{0, 0, 0}, {1, 0, 1}, {0, 1, 2}});
  const Coordinates target = points({{50, -3, 0.5}, {-7, 20, 1.5}});  // far off in x and y
  mapper->initialize(source, target);
  RowMatrix values(3, 1);
  values << 10, 20, 40;
  const RowMatrix mapped = mapper->map(values);
  EXPECT_DOUBLE_EQ(mapped(0, 0), 15.0);
  EXPECT_DOUBLE_EQ(mapped(1, 0), 30.0);
  EXPECT_EQ(mapper->quality().max_distance, 0.0);
}

// --- unmatched targets ------------------------------------------------------------------------

class Unmatched : public ::testing::Test {
 protected:
  // Sources on the x axis; target 1 is 0.51 away from them (target 0 is 0.25 away).
  const Coordinates source = points({{0, 0, 0}, {1, 0, 0}});
  const Coordinates target = points({{0.25, 0, 0}, {0.9, 0.5, 0}});
  RowMatrix values() const {
    RowMatrix v(2, 2);
    v << 1, 2, 3, 4;
    return v;
  }
  std::unique_ptr<Interpolator> mapper(const std::string& policy) const {
    auto m = make_interpolator("type: linear\ndirections: [x, y]\nmax_distance: 0.3\nunmatched: " +
                               policy);
    m->initialize(source, target);
    return m;
  }
};

TEST_F(Unmatched, ZeroGivesZeroRows) {
  auto m = mapper("zero");
  const RowMatrix mapped = m->map(values());
  EXPECT_DOUBLE_EQ(mapped(0, 0), 1.5);
  EXPECT_DOUBLE_EQ(mapped(0, 1), 2.5);
  EXPECT_EQ(mapped.row(1), Eigen::RowVector2d(0, 0));
  EXPECT_EQ(m->quality().unmatched, 1);
  // Transpose: the unmatched target's force is dropped.
  RowMatrix forces(2, 2);
  forces << 4, 0, 100, 100;
  const RowMatrix back = m->map_transpose(forces);
  EXPECT_DOUBLE_EQ(back(0, 0), 3.0);
  EXPECT_DOUBLE_EQ(back(1, 0), 1.0);
  EXPECT_DOUBLE_EQ(back.col(1).sum(), 0.0);
}

TEST_F(Unmatched, NearestTakesTheNearestSourceValue) {
  auto m = mapper("nearest");
  const RowMatrix mapped = m->map(values());
  EXPECT_EQ(mapped.row(1), Eigen::RowVector2d(3, 4));
  RowMatrix forces(2, 2);
  forces << 4, 0, 100, 100;
  const RowMatrix back = m->map_transpose(forces);
  EXPECT_DOUBLE_EQ(back(0, 0), 3.0);
  EXPECT_DOUBLE_EQ(back(1, 0), 101.0);
  EXPECT_DOUBLE_EQ(back.col(1).sum(), 100.0);
}

TEST_F(Unmatched, ErrorNamesTheTarget) {
  expect_error<std::invalid_argument>([&] { mapper("error"); },
                                      "target point 1 at (0.9, 0.5) (directions x, y) is 0.5");
}

TEST_F(Unmatched, NoLimitByDefault) {
  auto m = make_interpolator("type: linear\ndirections: [x, y]");
  m->initialize(source, target);
  EXPECT_EQ(m->quality().unmatched, 0);
  EXPECT_DOUBLE_EQ(m->map(values())(1, 0), 2.8);
}

// --- quality report ---------------------------------------------------------------------------

TEST(InterpolatorQuality, NearestDistances) {
  auto mapper = make_interpolator("type: nearest\ndirections: [x]");
  mapper->initialize(points({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}), points({{0.5, 0, 0}, {3, 0, 0}}));
  EXPECT_DOUBLE_EQ(mapper->quality().min_distance, 0.5);
  EXPECT_DOUBLE_EQ(mapper->quality().mean_distance, 0.75);
  EXPECT_DOUBLE_EQ(mapper->quality().max_distance, 1.0);
  EXPECT_EQ(mapper->quality().fallbacks, 0);
}

TEST(InterpolatorQuality, LinearCountsClampedTargetsAsFallbacks) {
  auto mapper = make_interpolator("type: linear\ndirections: [x]");
  mapper->initialize(points({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}), points({{0.5, 0, 0}, {3, 0, 0}}));
  EXPECT_DOUBLE_EQ(mapper->quality().min_distance, 0.0);
  EXPECT_DOUBLE_EQ(mapper->quality().mean_distance, 0.5);
  EXPECT_DOUBLE_EQ(mapper->quality().max_distance, 1.0);
  EXPECT_EQ(mapper->quality().fallbacks, 1);
}

TEST(InterpolatorQuality, LinearDistanceToTheTriangle) {
  // A unit square in z = 0; targets 0.25 above its inside, and one beside it (segment fallback).
  auto mapper = make_interpolator("type: linear");
  mapper->initialize(points({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}),
                     points({{0.3, 0.2, 0.25}, {0.6, 0.7, 0.25}, {0.5, -0.5, 0}}));
  EXPECT_DOUBLE_EQ(mapper->quality().min_distance, 0.25);
  EXPECT_DOUBLE_EQ(mapper->quality().max_distance, 0.5);
  EXPECT_EQ(mapper->quality().fallbacks, 1);
}

}  // namespace
}  // namespace cocopp::testing
